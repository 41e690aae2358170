// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the HiZ pyramid's layout, the one home of
// what the host sizes and dispatches (features/visbuffer/hiz_pyramid.hpp) and what the shaders
// index (visbuffer/hiz_occlusion.glsl, hiz_build.comp). The pyramid is one buffer of 32-bit depth
// keys: levels k >= 1 of ceil(W / 2^k) x ceil(H / 2^k) texels, row major, one after another from
// level 1 (level 0, the pixels themselves, is not stored).
#ifndef FGB_RENDERER_SHARED_HIZ_H
#define FGB_RENDERER_SHARED_HIZ_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/visbuffer.h"  // FGB_HIZ_PASS_LEVELS

FGB_GPU_BEGIN

// A viewport side at level `level`: ceil(side / 2^level).
FGB_INLINE uint hizLevelSide(uint side, uint level) {
  return (side + (1u << level) - 1u) >> level;
}

// Levels until the top one is a single texel (at least 1): ceil(log2(max(W, H))).
FGB_INLINE uint hizLevels(uint width, uint height) {
  uint level = 1u;
  while (hizLevelSide(width, level) > 1u || hizLevelSide(height, level) > 1u) ++level;
  return level;
}

// Offset (in keys) of level `level` >= 1; of level hizLevels + 1, the pyramid's size in keys.
FGB_INLINE uint hizLevelOffset(uint width, uint height, uint level) {
  uint offset = 0u;
  for (uint k = 1u; k < level; ++k) offset += hizLevelSide(width, k) * hizLevelSide(height, k);
  return offset;
}

// "HiZ Build"'s dispatches: pass p reads level p * FGB_HIZ_PASS_LEVELS (level 0: the depths) and
// writes the FGB_HIZ_PASS_LEVELS levels after it, one workgroup per texel of the pass's last level
// (ceil(ceil(W / 2^a) / 2^b) = ceil(W / 2^(a + b))), with a compute barrier between passes.
FGB_INLINE uint hizPasses(uint width, uint height) {
  return (hizLevels(width, height) + FGB_HIZ_PASS_LEVELS - 1u) / FGB_HIZ_PASS_LEVELS;
}
FGB_INLINE uint hizPassGroupsAlong(uint side, uint pass) {
  return hizLevelSide(side, (pass + 1u) * FGB_HIZ_PASS_LEVELS);
}

FGB_GPU_END

#endif
