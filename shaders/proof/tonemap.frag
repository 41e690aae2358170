#version 460
// Tone mapping (thesis): L = 1 - exp(-L_hdr * exposure), written to an sRGB target.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"

layout(push_constant) uniform Push {
  uint hdrTexture;
  uint pointSampler;
  float exposure;
} pc;
layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 hdr = fgbSample(pc.hdrTexture, pc.pointSampler, inUv).rgb;
  outColor = vec4(1.0 - exp(-hdr * pc.exposure), 1.0);
}
