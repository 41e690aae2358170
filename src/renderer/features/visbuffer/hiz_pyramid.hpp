// The HiZ pyramid's layout on the host (render.occlusion; the GLSL side is
// shaders/renderer/visbuffer/hiz_occlusion.glsl): levels k >= 1 of ceil(W / 2^k) x ceil(H / 2^k)
// 32-bit depth keys, one after another in one buffer. Used by the visibility-buffer and meshlet
// paths, which build it from their own depths ("HiZ Build", hiz_build.comp and its variant "depth":
// FGB_HIZ_PASS_LEVELS levels a dispatch, two dispatches up to 4096 pixels a side).
#pragma once

#include <cstdint>

#include "renderer/shared/scene.h"
#include "renderer/shared/visbuffer.h"  // FGB_HIZ_PASS_LEVELS

namespace fgb::features {

// A viewport side at a HiZ pyramid level: ceil(size / 2^level) (hizLevelSize in hiz_occlusion.glsl).
inline uint32_t hizLevelSize(uint32_t size, uint32_t level) {
  return (size + (1u << level) - 1) >> level;
}
// The HiZ pyramid's levels (>= 1; see hiz_occlusion.glsl) and its size in 32-bit keys.
inline uint32_t hizLevels(uint32_t width, uint32_t height) {
  uint32_t level = 1;
  while (hizLevelSize(width, level) > 1 || hizLevelSize(height, level) > 1) ++level;
  return level;
}
// "HiZ Build"'s dispatches (hizPasses and hizPassGroups in hiz_occlusion.glsl): pass p reads level
// p * FGB_HIZ_PASS_LEVELS (0: the depths) and writes the levels after it, one workgroup per texel
// of the pass's last level; a compute barrier between passes.
inline uint32_t hizPasses(uint32_t width, uint32_t height) {
  return (hizLevels(width, height) + FGB_HIZ_PASS_LEVELS - 1) / FGB_HIZ_PASS_LEVELS;
}
struct HizGroups {
  uint32_t x, y;
};
inline HizGroups hizPassGroups(uint32_t width, uint32_t height, uint32_t pass) {
  const uint32_t lastLevel = (pass + 1) * FGB_HIZ_PASS_LEVELS;
  return {hizLevelSize(width, lastLevel), hizLevelSize(height, lastLevel)};
}
inline uint64_t hizKeys(uint32_t width, uint32_t height) {
  uint64_t keys = 0;
  const uint32_t levels = hizLevels(width, height);
  for (uint32_t level = 1; level <= levels; ++level)
    keys += uint64_t{hizLevelSize(width, level)} * hizLevelSize(height, level);
  return keys;
}

// Reversed Z: the projection maps nearer points to larger depth (the depth keys' convention).
inline bool projectsReversedZ(const gpu::FrameConstants& constants) {
  const float near = constants.depthRange.x;
  const auto depthAt = [&](float distance) {
    const glm::vec4 clip = constants.proj * glm::vec4(0.0f, 0.0f, -distance, 1.0f);
    return clip.z / clip.w;
  };
  return depthAt(2.0f * near) > depthAt(4.0f * near);
}

}  // namespace fgb::features
