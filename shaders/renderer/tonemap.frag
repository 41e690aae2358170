#version 460
// "Tone mapping" (thesis): L = 1 - exp(-L_hdr * exposure), plus the bloom texture when present,
// written to an sRGB target (the hardware applies the sRGB curve). The HDR image is pre-exposed
// (L_hdr * preExposure): the exposure left to apply is the state's tonemapScale.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"

layout(push_constant) uniform Push {
  uint hdrTexture;
  uint bloomTexture;  // FGB_NONE: no bloom
  uint linearSampler;
  uint exposure;  // storage-buffer index of the exposure state
  float bloomIntensity;
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 hdr = texelFetch(fgbTextures[pc.hdrTexture], ivec2(gl_FragCoord.xy), 0).rgb;
  if (pc.bloomTexture != FGB_NONE) hdr += pc.bloomIntensity * fgbSample(pc.bloomTexture, pc.linearSampler, inUv).rgb;
  float scale = fgbExposures[pc.exposure].state.tonemapScale;
  outColor = vec4(1.0 - exp(-max(hdr, vec3(0.0)) * scale), 1.0);
}
