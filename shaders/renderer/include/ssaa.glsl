// "SSAA Resolve": output pixel p = mean of the supersampled HDR image's factor x factor block
// starting at p * factor (a box filter; see src/renderer/features/ssaa/ssaa_resolve_feature.hpp).
// The summation order is fixed, so the result is deterministic. Shared by ssaa_resolve.frag
// (forward path) and ssaa_resolve.comp (visibility-buffer path).
#ifndef FGB_SSAA_GLSL
#define FGB_SSAA_GLSL

#include "common.glsl"
#include "renderer/shared/post.h"

layout(push_constant) uniform Push { SsaaResolvePush pc; };

vec4 ssaaBoxMean(ivec2 outputPixel) {
  const ivec2 base = outputPixel * int(pc.factor);
  vec4 sum = vec4(0.0);
  for (int y = 0; y < int(pc.factor); ++y)
    for (int x = 0; x < int(pc.factor); ++x) sum += fgbFetch(pc.source, base + ivec2(x, y));
  return sum / float(pc.factor * pc.factor);
}

#endif
