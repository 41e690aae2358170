#version 460
// Bloom downsample (Jimenez, CoD:AW 2014): 13-tap filter as five overlapping 2x2 boxes. The first
// downsample weights each box by Karis' 1/(1 + luma) against fireflies, then applies the soft
// threshold prefilter.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"

layout(push_constant) uniform Push {
  uint source;
  uint linearSampler;
  vec2 sourceTexel;   // 1 / source size
  uint firstMip;
  float threshold;
  float knee;
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

vec3 tap(vec2 offset) { return fgbSample(pc.source, pc.linearSampler, inUv + offset * pc.sourceTexel).rgb; }

float karisWeight(vec3 c) { return 1.0 / (1.0 + luminance(c)); }

vec3 softThreshold(vec3 c) {
  const float bias = 1e-4;
  float brightness = max(c.r, max(c.g, c.b));
  float soft = clamp(brightness - pc.threshold + pc.threshold * pc.knee, 0.0, 2.0 * pc.threshold * pc.knee);
  soft = soft * soft / (4.0 * (pc.threshold * pc.knee + bias));
  return c * max(soft, brightness - pc.threshold) / max(brightness, bias);
}

void main() {
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
    sum = softThreshold(sum / max(total, 1e-6));
  } else {
    for (int n = 0; n < 5; ++n) sum += boxes[n] * weights[n];
  }
  outColor = vec4(max(sum, vec3(0.0)), 1.0);
}
