#version 460
// Bloom downsample (Jimenez, CoD:AW 2014), one level of the "Bloom" node: a 13-tap filter as five
// overlapping 2x2 boxes. The first downsample (from the HDR image, sampled) weights each box by
// Karis' 1/(1 + luma) against fireflies, then applies the soft-threshold prefilter; later ones
// sample the previous level (written by the dispatch before, include/bloom.glsl) with the same taps.
#extension GL_GOOGLE_include_directive : require
#include "include/bloom.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_BLOOM_GROUP_SIZE, local_size_y = FGB_BLOOM_GROUP_SIZE) in;

layout(push_constant) uniform Push { BloomDownPush pc; };

vec2 gUv;  // centre of this invocation's target texel
vec2 gSourceTexel;

vec3 tap(vec2 offset) { return bilinearTap(pc.source, pc.linearSampler, gUv + offset * gSourceTexel); }

float karisWeight(vec3 c) { return 1.0 / (1.0 + luminance(c)); }

// Karis' weight and the threshold see pre-exposed values (display-range, whatever the scene's
// absolute radiance), so a scene whose lights and exposure are scaled inversely blooms the same.
vec3 softThreshold(vec3 c, float threshold) {
  const float bias = 1e-4;
  float brightness = max(c.r, max(c.g, c.b));
  float soft = clamp(brightness - threshold + threshold * pc.knee, 0.0, 2.0 * threshold * pc.knee);
  soft = soft * soft / (4.0 * (threshold * pc.knee + bias));
  return c * max(soft, brightness - threshold) / max(brightness, bias);
}

void main() {
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, pc.targetSize))) return;
  gUv = (vec2(texel) + 0.5) / vec2(pc.targetSize);
  gSourceTexel = 1.0 / vec2(pc.sourceSize);
  vec3 a = tap(vec2(-2, -2)), b = tap(vec2(0, -2)), c = tap(vec2(2, -2));
  vec3 d = tap(vec2(-1, -1)), e = tap(vec2(1, -1));
  vec3 f = tap(vec2(-2, 0)), g = tap(vec2(0, 0)), h = tap(vec2(2, 0));
  vec3 i = tap(vec2(-1, 1)), j = tap(vec2(1, 1));
  vec3 k = tap(vec2(-2, 2)), l = tap(vec2(0, 2)), m = tap(vec2(2, 2));
  vec3 boxes[5] = vec3[5]((d + e + i + j) * 0.25, (a + b + f + g) * 0.25, (b + c + g + h) * 0.25,
                          (f + g + k + l) * 0.25, (g + h + l + m) * 0.25);
  const float weights[5] = float[5](0.5, 0.125, 0.125, 0.125, 0.125);
  vec3 sum = vec3(0.0);
  if (pc.firstMip != 0u) {
    float total = 0.0;
    for (int n = 0; n < 5; ++n) {
      float w = weights[n] * karisWeight(boxes[n]);
      sum += boxes[n] * w;
      total += w;
    }
    sum = softThreshold(sum / max(total, 1e-6), pc.threshold * fgbExposures[pc.exposure].state.preExposure);
  } else {
    for (int n = 0; n < 5; ++n) sum += boxes[n] * weights[n];
  }
  vec4 result = vec4(clamp(sum, vec3(0.0), vec3(kHalfMax)), 1.0);
  if (pc.inject == kInjectNan && texel == pc.targetSize / 2) result.r = uintBitsToFloat(0x7fc00000u);
  imageStore(fgbImagesRgba16f[pc.target], texel, result);
}
