// The FLIP evaluation engine (private to the flip room): the error map of a reference and a test image,
// strip-tiled over the worker threads, for LDR-FLIP (one pass) and HDR-FLIP (one pass per exposure).
#pragma once

#include <fgb/harness/flip/flip.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace fgb::harness::flip_detail {

// What to compare. Both images are width * height RGBA floats, row-major.
struct EngineSources {
  uint32_t width = 0, height = 0;
  std::array<const float*, 2> rgba{};  // reference, test
  std::array<bool, 2> srgb{};          // display images: sRGB-encoded, else linear
  bool toneMap = false;                // HDR: ACES of scale * value, one pass per scale
  std::vector<float> scales{1.0f};
};

// The error map of the two sources (one pass per exposure scale; the maximum over the passes).
FlipMap runEngine(EngineSources sources, double ppd);

}  // namespace fgb::harness::flip_detail
