#version 460
// "SSAA Resolve": output pixel p = mean of the supersampled HDR image's factor x factor block
// starting at p * factor (a box filter; see src/renderer/features/ssaa/ssaa_resolve_feature.hpp).
// The summation order is fixed, so the result is deterministic.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"

layout(push_constant) uniform Push {
  uint source;  // sampled texture index of the supersampled HDR image
  uint factor;  // render.ssaa, 2..4
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  const ivec2 base = ivec2(gl_FragCoord.xy) * int(pc.factor);
  vec4 sum = vec4(0.0);
  for (int y = 0; y < int(pc.factor); ++y)
    for (int x = 0; x < int(pc.factor); ++x) sum += fgbFetch(pc.source, base + ivec2(x, y));
  outColor = sum / float(pc.factor * pc.factor);
}
