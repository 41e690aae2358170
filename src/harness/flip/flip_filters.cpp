#include "flip_filters.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace fgb::harness::flip_detail {

double sumOf(const Kernel& k) { return std::accumulate(k.taps.begin(), k.taps.end(), 0.0); }

void scale(Kernel& k, double factor) {
  for (float& t : k.taps) t = static_cast<float>(t * factor);
}

void normalizeSignedParts(Kernel& k) {
  double positive = 0.0;
  double negative = 0.0;
  for (float t : k.taps) (t > 0 ? positive : negative) += t;
  for (float& t : k.taps) {
    if (t > 0 && positive > 0) t = static_cast<float>(t / positive);
    if (t < 0 && negative < 0) t = static_cast<float>(t / -negative);
  }
}

void detectSymmetry(Kernel& k) {
  bool even = true, odd = true;
  const std::size_t n = k.taps.size();
  for (std::size_t i = 0; i < n; ++i) {
    even = even && k.taps[i] == k.taps[n - 1 - i];
    odd = odd && k.taps[i] == -k.taps[n - 1 - i];
  }
  k.symmetry = even ? 1 : (odd ? -1 : 0);
}

void trimNegligibleTaps(Kernel& k, double relative) {
  float largest = 0.0f;
  for (float t : k.taps) largest = std::max(largest, std::abs(t));
  int keep = k.radius;
  while (keep > 0 && std::abs(k.taps[static_cast<std::size_t>(k.radius - keep)]) < relative * largest &&
         std::abs(k.taps[static_cast<std::size_t>(k.radius + keep)]) < relative * largest) {
    --keep;
  }
  const auto drop = static_cast<std::ptrdiff_t>(k.radius - keep);
  k.taps = std::vector<float>(k.taps.begin() + drop, k.taps.end() - drop);
  k.radius = keep;
}

FoldedKernel fold(const Kernel& k) {
  if (k.symmetry == 0) throw std::logic_error("FLIP: kernels must be even or odd");
  FoldedKernel f;
  f.radius = k.radius;
  f.odd = k.symmetry < 0;
  f.centre = f.odd ? 0.0f : k.taps[static_cast<std::size_t>(k.radius)];
  f.side.assign(static_cast<std::size_t>(k.radius) + 1, 0.0f);
  for (int i = 1; i <= k.radius; ++i) f.side[static_cast<std::size_t>(i)] = k.taps[static_cast<std::size_t>(k.radius + i)];
  return f;
}

FoldedKernel padTo(FoldedKernel k, int radius) {
  if (radius > k.radius) {
    k.side.resize(static_cast<std::size_t>(radius) + 1, 0.0f);
    k.radius = radius;
  }
  return k;
}

}  // namespace fgb::harness::flip_detail
