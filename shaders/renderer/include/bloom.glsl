// Shared by the bloom compute shaders. The chain's levels (after level 0, the HDR image) are
// storage images in the GENERAL layout for the whole "Bloom" node: each dispatch writes one level
// with imageStore, and the next one filters it through a sampled descriptor in GENERAL
// (graph::Access::StorageSampledWrite) with the linear clamp-to-edge sampler, so the texture unit
// does each bilinear tap's 4-texel blend.
#ifndef FGB_BLOOM_GLSL
#define FGB_BLOOM_GLSL

#include "common.glsl"

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) uniform image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

// One bilinear tap of a level (its only mip) at `uv` (texel centres at (i + 0.5) / size).
vec3 bilinearTap(uint texture, uint linearClampSampler, vec2 uv) {
  return textureLod(sampler2D(fgbTextures[texture], fgbSamplers[linearClampSampler]), uv, 0.0).rgb;
}

#endif
