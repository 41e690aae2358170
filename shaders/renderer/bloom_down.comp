#version 460
// Bloom downsample (Jimenez, CoD:AW 2014), one level of the "Bloom" node: a 13-tap filter as five
// overlapping 2x2 boxes. The first downsample (from the HDR image, sampled) weights each box by
// Karis' 1/(1 + luma) against fireflies, then applies the soft-threshold prefilter; later ones read
// the previous level (a storage image) with the same bilinear taps.
#extension GL_GOOGLE_include_directive : require
#include "include/bloom.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_BLOOM_GROUP_SIZE, local_size_y = FGB_BLOOM_GROUP_SIZE) in;

layout(push_constant) uniform Push { BloomDownPush pc; };

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
  vec3 sum = vec3(0.0);
  if (pc.firstMip != 0u) {
    vec3 boxes[5];
    bloomDownBoxes(pc.source, pc.sourceIsStorage == 0u, pc.linearSampler, pc.sourceSize, pc.targetSize, texel, boxes);
    float total = 0.0;
    for (int n = 0; n < 5; ++n) {
      float w = kBloomBoxWeights[n] * karisWeight(boxes[n]);
      sum += boxes[n] * w;
      total += w;
    }
    sum = softThreshold(sum / max(total, 1e-6), pc.threshold * fgbExposures[pc.exposure].state.preExposure);
  } else {
    sum = bloomDownsampleLevel(pc.source, pc.sourceSize, pc.targetSize, texel);
  }
  vec4 result = vec4(clamp(sum, vec3(0.0), vec3(kHalfMax)), 1.0);
  if (pc.inject == kInjectNan && texel == pc.targetSize / 2) result.r = uintBitsToFloat(0x7fc00000u);
  imageStore(fgbImagesRgba16f[pc.target], texel, result);
}
