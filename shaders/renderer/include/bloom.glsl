// Shared by the bloom compute shaders: the chain's levels (after level 0, the HDR image) are
// storage images in the GENERAL layout for the whole "Bloom" node, so they are read with
// imageLoad and filtered here (bilinear, clamp to edge) instead of through a sampler.
#ifndef FGB_BLOOM_GLSL
#define FGB_BLOOM_GLSL

#include "common.glsl"

// bloom_tail.comp reads levels it wrote itself a workgroup barrier earlier: its images are coherent.
#ifndef FGB_BLOOM_IMAGE_QUALIFIERS
#define FGB_BLOOM_IMAGE_QUALIFIERS
#endif
layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) FGB_BLOOM_IMAGE_QUALIFIERS uniform image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

vec3 loadClamped(uint image, ivec2 texel, ivec2 size) {
  return imageLoad(fgbImagesRgba16f[image], clamp(texel, ivec2(0), size - 1)).rgb;
}

// What a linear clamp-to-edge sampler returns at `uv` (texel centres at (i + 0.5) / size).
vec3 bilinearLoad(uint image, vec2 uv, ivec2 size) {
  const vec2 position = uv * vec2(size) - 0.5;
  const ivec2 base = ivec2(floor(position));
  const vec2 f = position - vec2(base);
  const vec3 a = loadClamped(image, base, size);
  const vec3 b = loadClamped(image, base + ivec2(1, 0), size);
  const vec3 c = loadClamped(image, base + ivec2(0, 1), size);
  const vec3 d = loadClamped(image, base + ivec2(1, 1), size);
  return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// One tap of the downsample at `uv`: through the sampler (the HDR image, a sampled texture) or
// filtered here (a level of the chain, a storage image).
vec3 bloomDownTap(uint source, bool sampled, uint linearSampler, vec2 uv, ivec2 sourceSize) {
  if (sampled) return fgbSample(source, linearSampler, uv).rgb;
  return bilinearLoad(source, uv, sourceSize);
}

// The downsample of Jimenez (CoD:AW 2014) at `texel` of the target: 13 taps as five overlapping
// 2x2 boxes, the centre box first.
void bloomDownBoxes(uint source, bool sampled, uint linearSampler, ivec2 sourceSize, ivec2 targetSize, ivec2 texel,
                    out vec3 boxes[5]) {
  const vec2 uv = (vec2(texel) + 0.5) / vec2(targetSize);
  const vec2 step = 1.0 / vec2(sourceSize);
#define FGB_TAP(x, y) bloomDownTap(source, sampled, linearSampler, uv + vec2(x, y) * step, sourceSize)
  vec3 a = FGB_TAP(-2, -2), b = FGB_TAP(0, -2), c = FGB_TAP(2, -2);
  vec3 d = FGB_TAP(-1, -1), e = FGB_TAP(1, -1);
  vec3 f = FGB_TAP(-2, 0), g = FGB_TAP(0, 0), h = FGB_TAP(2, 0);
  vec3 i = FGB_TAP(-1, 1), j = FGB_TAP(1, 1);
  vec3 k = FGB_TAP(-2, 2), l = FGB_TAP(0, 2), m = FGB_TAP(2, 2);
#undef FGB_TAP
  boxes = vec3[5]((d + e + i + j) * 0.25, (a + b + f + g) * 0.25, (b + c + g + h) * 0.25, (f + g + k + l) * 0.25,
                  (g + h + l + m) * 0.25);
}

const float kBloomBoxWeights[5] = float[5](0.5, 0.125, 0.125, 0.125, 0.125);

// A level after the first from the one before it (a storage image): the boxes' weighted sum.
vec3 bloomDownsampleLevel(uint source, ivec2 sourceSize, ivec2 targetSize, ivec2 texel) {
  vec3 boxes[5];
  bloomDownBoxes(source, false, 0u, sourceSize, targetSize, texel, boxes);
  vec3 sum = vec3(0.0);
  for (int n = 0; n < 5; ++n) sum += boxes[n] * kBloomBoxWeights[n];
  return sum;
}

// The upsample: a 3x3 tent (1 2 1 / 2 4 2 / 1 2 1) / 16 of the smaller level at `texel` of the
// larger, `radius` source texels apart.
vec3 bloomUpsampleTent(uint source, ivec2 sourceSize, ivec2 targetSize, ivec2 texel, float radius) {
  const vec2 uv = (vec2(texel) + 0.5) / vec2(targetSize);
#define FGB_TAP(x, y) bilinearLoad(source, uv + vec2(x, y) * radius / vec2(sourceSize), sourceSize)
  vec3 sum = FGB_TAP(-1, -1) + 2.0 * FGB_TAP(0, -1) + FGB_TAP(1, -1) + 2.0 * FGB_TAP(-1, 0) + 4.0 * FGB_TAP(0, 0) +
             2.0 * FGB_TAP(1, 0) + FGB_TAP(-1, 1) + 2.0 * FGB_TAP(0, 1) + FGB_TAP(1, 1);
#undef FGB_TAP
  return sum / 16.0;
}

#endif
