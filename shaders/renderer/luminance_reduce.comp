#version 460
// "Exposure", first dispatch: each workgroup sums log2(luminance) over a 32x32-pixel block of the
// pre-exposed HDR image (2x2 pixels per invocation, then a fixed-order tree in shared memory, so the
// result is the same every run) and stores (sum, count) for exposure_update.comp. Pixels the
// background clear left alone (alpha 0) are not measured: only lit geometry sets the exposure.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/exposure.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_LUMINANCE_GROUP_SIZE, local_size_y = FGB_LUMINANCE_GROUP_SIZE) in;

layout(push_constant) uniform Push { LuminanceReducePush pc; };

shared vec2 sharedSums[256];

void main() {
  vec2 sum = vec2(0.0);
  ivec2 origin = ivec2(gl_GlobalInvocationID.xy) * 2;
  for (int n = 0; n < 4; ++n) {
    ivec2 texel = origin + ivec2(n & 1, n >> 1);
    if (any(greaterThanEqual(texel, pc.size))) continue;
    vec4 hdr = fgbFetch(pc.hdr, texel);
    if (!(hdr.a > 0.0)) continue;  // background (or NaN alpha)
    sum += vec2(log2PreExposedLuminance(hdr.rgb), 1.0);
  }
  uint index = gl_LocalInvocationIndex;
  sharedSums[index] = sum;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (index < stride) sharedSums[index] += sharedSums[index + stride];
    barrier();
  }
  if (index == 0u) {
    uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    fgbVec4s[pc.partials].values[group] = vec4(sharedSums[0], 0.0, 0.0);
  }
}
