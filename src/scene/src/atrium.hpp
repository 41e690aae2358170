// Private: the atrium generator (see generators.hpp).
#pragma once

#include <fgb/scene/scene.hpp>

namespace fgb::scene {

// The thesis' Sponza + brazier statistics the default atrium reproduces.
inline constexpr uint64_t kThesisTriangles = 3781554;
inline constexpr uint32_t kThesisInstances = 115;
inline constexpr uint32_t kThesisLights = 28;

struct AtriumParams {
  double scale = 1.0;         // geometry density multiplier
  uint32_t seed = 1;
  uint32_t textureSize = 512;
};

Scene buildAtrium(const AtriumParams& params);

}  // namespace fgb::scene
