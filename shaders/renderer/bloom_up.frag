#version 460
// Bloom upsample: 3x3 tent (1 2 1 / 2 4 2 / 1 2 1) / 16 of the smaller mip, added (blend) onto
// the next larger one.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"

layout(push_constant) uniform Push {
  uint source;
  uint linearSampler;
  vec2 sourceTexel;
  float radius;  // in source texels
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

vec3 tap(float x, float y) {
  return fgbSample(pc.source, pc.linearSampler, inUv + vec2(x, y) * pc.sourceTexel * pc.radius).rgb;
}

void main() {
  vec3 sum = tap(-1, -1) + 2.0 * tap(0, -1) + tap(1, -1) + 2.0 * tap(-1, 0) + 4.0 * tap(0, 0) + 2.0 * tap(1, 0) +
             tap(-1, 1) + 2.0 * tap(0, 1) + tap(1, 1);
  outColor = vec4(sum / 16.0, 1.0);
}
