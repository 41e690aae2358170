// Shared by the bloom compute shaders: the chain's levels (after level 0, the HDR image) are
// storage images in the GENERAL layout for the whole "Bloom" node, so they are read with
// imageLoad and filtered here (bilinear, clamp to edge) instead of through a sampler.
#ifndef FGB_BLOOM_GLSL
#define FGB_BLOOM_GLSL

#include "common.glsl"

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) uniform image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

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

#endif
