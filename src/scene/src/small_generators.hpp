// Private: the showcase and stress generators (see generators.hpp).
#pragma once

#include <fgb/scene/geometry.hpp>

#include "atrium.hpp"

#include <functional>
#include <string>

namespace fgb::scene {

struct ShowcaseParams {
  uint32_t objects = 9;
  AlphaMode alpha = AlphaMode::Opaque;
  bool floor = true;
  uint32_t lights = 4;
  bool emissive = false;
  bool sun = true;
  uint32_t seed = 1;
};

// `corrupt` (optional) sees every mesh before its repair: stress-nan laces it with NaN/Inf.
Scene buildShowcase(const ShowcaseParams& params, const std::string& context,
                    const std::function<void(MeshData&)>& corrupt = {});

Scene buildStressFar(const AtriumParams& atrium, double offset);
Scene buildStressDepth(const AtriumParams& atrium);
Scene buildStressLights(const AtriumParams& atrium, uint32_t count, uint32_t seed);
Scene buildStressTriangles(uint32_t count, uint32_t seed);
Scene buildStressNan(double fraction, uint32_t seed);

}  // namespace fgb::scene
