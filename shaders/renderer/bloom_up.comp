#version 460
// Bloom upsample, one level of the "Bloom" node: a 3x3 tent (1 2 1 / 2 4 2 / 1 2 1) / 16 of the
// smaller level, added onto the next larger one in place (each invocation reads and writes only
// its own texel of the target).
#extension GL_GOOGLE_include_directive : require
#include "include/bloom.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_BLOOM_GROUP_SIZE, local_size_y = FGB_BLOOM_GROUP_SIZE) in;

layout(push_constant) uniform Push { BloomUpPush pc; };

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, pc.targetSize))) return;
  const vec3 sum = bloomUpsampleTent(pc.source, pc.sourceSize, pc.targetSize, texel, pc.radius);
  const vec4 below = imageLoad(fgbImagesRgba16f[pc.target], texel);
  // Adding levels can pass the half-float maximum: saturate rather than store Inf.
  vec4 result = vec4(min(below.rgb + sum, vec3(kHalfMax)), 1.0);
  if (pc.inject == kInjectNan && texel == pc.targetSize / 2) result.r = uintBitsToFloat(0x7fc00000u);
  if (pc.inject == kInjectBias) result.rgb += kInjectedBias;
  imageStore(fgbImagesRgba16f[pc.target], texel, result);
}
