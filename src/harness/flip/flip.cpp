// FLIP, following the structure of the paper: a colour pipeline (opponent space, contrast
// sensitivity filtering, Hunt-adjusted L*a*b*, HyAB distance, error redistribution) and a feature
// pipeline (edges and points on luminance), combined as dE_c^(1 - dE_f).
//
// This file is the public API; the colour model and the kernels are in flip_model.hpp/.cpp, the
// strip-tiled evaluation engine in flip_engine.cpp and its filters in flip_filters.hpp/.cpp.
#include <fgb/harness/flip/flip.hpp>

#include <fgb/harness/base/parallel.hpp>
#include <fgb/harness/stats/order_statistics.hpp>

#include "flip_engine.hpp"
#include "flip_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <utility>

namespace fgb::harness {
namespace {

using flip_detail::kAces0;
using flip_detail::kAces1;
using flip_detail::kAces3;
using flip_detail::kAces4;
using flip_detail::kAces5;
using flip_detail::nonNegativeFinite;

void requireSameSize(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument("FLIP: image sizes differ (" + describeSize(a) + " vs " + describeSize(b) + ")");
  }
  if (a.width == 0 || a.height == 0) throw std::invalid_argument("FLIP: empty image");
}

float finiteOrZero(float v) { return std::isfinite(v) ? v : 0.0f; }

// The x with ACES(x) = t (the positive root of the quadratic).
double acesInverse(double t) {
  const double c0 = (kAces1 - kAces4 * t) / (kAces0 - kAces3 * t);
  const double c1 = (0.0 - kAces5 * t) / (kAces0 - kAces3 * t);
  return -0.5 * c0 + std::sqrt(0.25 * c0 * c0 - c1);
}

// The ACES curve of an already exposed, non-negative value.
float acesCurve(double x) {
  const double mapped = (kAces0 * x * x + kAces1 * x) / (kAces3 * x * x + kAces4 * x + kAces5);
  return static_cast<float>(std::clamp(std::isfinite(mapped) ? mapped : 1.0, 0.0, 1.0));
}

}  // namespace

double defaultPixelsPerDegree() { return 0.7 * 3840.0 / 0.7 * flip_detail::kPi / 180.0; }

FlipMap ldrFlip(const Image& reference, const Image& test, double pixelsPerDegree) {
  requireSameSize(reference, test);
  flip_detail::EngineSources in;
  in.width = reference.width;
  in.height = reference.height;
  in.rgba = {reference.rgba.data(), test.rgba.data()};
  in.srgb = {reference.encoding == Encoding::Srgb, test.encoding == Encoding::Srgb};
  return flip_detail::runEngine(std::move(in), pixelsPerDegree);
}

float acesToneMap(float value, double exposure) {
  return acesCurve(std::max(0.0, static_cast<double>(finiteOrZero(value))) * std::exp2(exposure));
}

ExposureRange hdrExposureRange(const Image& linearReference) {
  constexpr double kTarget = 0.85;  // tone-mapped value the extreme luminances are mapped to
  ExposureRange range;
  const std::size_t n = linearReference.pixelCount();
  if (n == 0) return range;
  // Luminance keys: max(0, Y) of finite luminances, 0 otherwise.
  const float* rgba = linearReference.rgba.data();
  const detail::OrderKeysOf keysOf = [rgba](std::size_t begin, std::size_t end, uint32_t* keys) {
    for (std::size_t i = begin; i < end; ++i) {
      const float* p = rgba + i * 4;
      keys[i - begin] = detail::orderKey(nonNegativeFinite(0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]));
    }
  };
  const std::vector<uint32_t> keys = detail::selectOrderKeys(n, keysOf, {n / 2, n - 1});
  const float yMax = detail::fromOrderKey(keys[1]);
  if (yMax <= 0.0f) return range;
  float yMedian = detail::fromOrderKey(keys[0]);
  if (yMedian <= 0.0f) {
    // A mostly black image: use the darkest lit pixel so the range still reaches the shadows.
    std::mutex mutex;
    float smallest = yMax;
    parallelFor(n, 1 << 16, [&](std::size_t begin, std::size_t end) {
      std::array<uint32_t, detail::kOrderKeyChunk> chunk{};
      const uint32_t zero = detail::orderKey(0.0f);
      uint32_t least = detail::orderKey(yMax);
      for (std::size_t b = begin; b < end; b += chunk.size()) {
        const std::size_t e = std::min(end, b + chunk.size());
        keysOf(b, e, chunk.data());
        for (std::size_t i = 0; i < e - b; ++i) least = chunk[i] > zero && chunk[i] < least ? chunk[i] : least;
      }
      std::lock_guard lock(mutex);
      smallest = std::min(smallest, detail::fromOrderKey(least));
    });
    yMedian = smallest;
  }
  const double x = acesInverse(kTarget);
  range.start = std::log2(x / yMax);
  range.stop = std::log2(x / yMedian);
  constexpr int kMaxExposures = 32;  // guards against pathological dynamic ranges
  range.count = std::clamp(static_cast<int>(std::ceil(range.stop - range.start)), 2, kMaxExposures);
  return range;
}

HdrFlipResult hdrFlip(const Image& reference, const Image& test, double pixelsPerDegree) {
  requireSameSize(reference, test);
  const ExposureRange range = hdrExposureRange(reference);
  HdrFlipResult result;
  result.startExposure = range.start;
  result.stopExposure = range.stop;
  result.exposures = range.count;
  const double step = (range.stop - range.start) / std::max(range.count - 1, 1);
  flip_detail::EngineSources in;
  in.width = reference.width;
  in.height = reference.height;
  in.rgba = {reference.rgba.data(), test.rgba.data()};
  in.toneMap = true;
  in.scales.clear();
  for (int i = 0; i < range.count; ++i) in.scales.push_back(static_cast<float>(std::exp2(range.start + i * step)));
  result.map = flip_detail::runEngine(std::move(in), pixelsPerDegree);
  return result;
}

}  // namespace fgb::harness
