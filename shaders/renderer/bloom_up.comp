#version 460
// Bloom upsample, one level of the "Bloom" node: a 3x3 tent (1 2 1 / 2 4 2 / 1 2 1) / 16 of the
// smaller level, added onto the next larger one in place (each invocation reads and writes only
// its own texel of the target).
#extension GL_GOOGLE_include_directive : require
#include "include/bloom.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_BLOOM_GROUP_SIZE, local_size_y = FGB_BLOOM_GROUP_SIZE) in;

layout(push_constant) uniform Push { BloomUpPush pc; };

vec2 gUv;

vec3 tap(float x, float y) {
  return bilinearTap(pc.source, pc.linearSampler, gUv + vec2(x, y) * pc.radius / vec2(pc.sourceSize));
}

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, pc.targetSize))) return;
  gUv = (vec2(texel) + 0.5) / vec2(pc.targetSize);
  vec3 sum = tap(-1, -1) + 2.0 * tap(0, -1) + tap(1, -1) + 2.0 * tap(-1, 0) + 4.0 * tap(0, 0) + 2.0 * tap(1, 0) +
             tap(-1, 1) + 2.0 * tap(0, 1) + tap(1, 1);
  const vec4 below = imageLoad(fgbImagesRgba16f[pc.target], texel);
  // Adding levels can pass the half-float maximum: saturate rather than store Inf.
  vec4 result = vec4(min(below.rgb + sum / 16.0, vec3(kHalfMax)), 1.0);
  if (pc.inject == kInjectNan && texel == pc.targetSize / 2) result.r = uintBitsToFloat(0x7fc00000u);
  if (pc.inject == kInjectBias) result.rgb += kInjectedBias;
  imageStore(fgbImagesRgba16f[pc.target], texel, result);
}
