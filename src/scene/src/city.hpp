// Private: the city generator (see generators.hpp), an occluder-rich scene for occlusion culling.
#pragma once

#include <fgb/scene/scene.hpp>

namespace fgb::scene {

struct CityParams {
  uint32_t blocks = 9;  // city blocks per side; streets run between and around them
  uint32_t seed = 1;
  uint32_t textureSize = 512;
};

// Street grid geometry shared by the generator, its tests and the scene files' camera paths:
// street centre lines at x = k * kCityPitch and z = k * kCityPitch for k in [-blocks/2,
// blocks - blocks/2], so the streets x = 0 and z = 0 and their neighbours at +-kCityPitch exist for
// every blocks >= 2 (a camera path along them flies any size of city).
inline constexpr float kCityPitch = 60.0f;        // street centre line to the next, m
inline constexpr float kCityStreetWidth = 16.0f;  // kerb to kerb plus both pavements, m

Scene buildCity(const CityParams& params);

}  // namespace fgb::scene
