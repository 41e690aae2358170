// The HiZ pyramid on the host (render.occlusion): its size and "HiZ Build"'s dispatches, from the
// layout in renderer/shared/hiz.h that the shaders share (levels k >= 1 of ceil(W / 2^k) x
// ceil(H / 2^k) 32-bit depth keys, one after another in one buffer). Used by the visibility-buffer
// and meshlet paths, which build it from their own depths ("HiZ Build", hiz_build.comp and its
// variant "depth": FGB_HIZ_PASS_LEVELS levels a dispatch, two dispatches up to 4096 pixels a side).
#pragma once

#include <cstdint>

#include "renderer/shared/hiz.h"
#include "renderer/shared/scene.h"

namespace fgb::features {

// The layout and the dispatches are renderer/shared/hiz.h's, which the shaders use too.
using gpu::hizLevels;
using gpu::hizPasses;
struct HizGroups {
  uint32_t x, y;
};
inline HizGroups hizPassGroups(uint32_t width, uint32_t height, uint32_t pass) {
  return {gpu::hizPassGroupsAlong(width, pass), gpu::hizPassGroupsAlong(height, pass)};
}
// The pyramid's size in keys: the offset of the level after its last.
inline uint64_t hizKeys(uint32_t width, uint32_t height) {
  return gpu::hizLevelOffset(width, height, hizLevels(width, height) + 1);
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
