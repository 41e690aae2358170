// Separable convolution helpers for FLIP (private to fgb_harness). Images are planar float rows;
// borders replicate the edge pixel (as the FLIP paper's reference evaluation does).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <cstdint>
#include <vector>

// Hot loops are built once for the baseline ISA and once for x86-64-v3 (AVX2 + FMA), chosen at load
// time, so portable binaries still run fast on current CPUs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FGB_VECTOR_CLONES __attribute__((target_clones("default", "arch=x86-64-v3")))
#else
#define FGB_VECTOR_CLONES
#endif

namespace fgb::harness::flip_detail {

// A 1D kernel on [-radius, radius]: taps[i] multiplies the sample at offset i - radius.
// symmetry +1 (even: Gaussians, second derivatives) or -1 (odd: first derivatives) halves the
// multiplications; 0 for anything else.
struct Kernel {
  int radius = 0;
  int symmetry = 0;
  std::vector<float> taps;
};

// Samples of f(i) for i in [-radius, radius], with the symmetry detected from the samples.
template <typename F>
Kernel sampleKernel(int radius, F f) {
  Kernel k;
  k.radius = radius;
  k.taps.resize(static_cast<std::size_t>(2 * radius + 1));
  for (int i = -radius; i <= radius; ++i) k.taps[static_cast<std::size_t>(i + radius)] = static_cast<float>(f(static_cast<double>(i)));
  return k;
}

double sumOf(const Kernel& k);
void scale(Kernel& k, double factor);
// Positive taps scaled to sum to 1 and negative taps to sum to -1 (FLIP's feature kernels).
void normalizeSignedParts(Kernel& k);
// Sets k.symmetry from the taps (exact comparison: kernels are sampled from even/odd functions).
void detectSymmetry(Kernel& k);
// Drops outer taps below `relative` times the largest one: a Gaussian's far tail is below float
// precision of the sum, and computing it only costs time.
void trimNegligibleTaps(Kernel& k, double relative);

// Horizontal pass of one row: out[x] = sum_i taps[i] * in[clamp(x + i - radius)].
// `padded` is scratch of at least width + 2 * radius floats.
void convolveRow(const float* in, float* out, uint32_t width, const Kernel& k, std::vector<float>& padded);

// Vertical pass producing columns [x0, x0 + count) of output row y of a plane (rows of `width`
// floats, `height` rows): out[x - x0] = sum_i taps[i] * plane[clamp(y + i - radius)][x].
// Callers walk down a narrow column block so the rows the taps read stay in cache.
void convolveColumnRow(const float* plane, uint32_t width, uint32_t height, uint32_t y, uint32_t x0, uint32_t count,
                       const Kernel& k, float* out);

// 2^x and x^e for the per-pixel loops: polynomial forms that vectorise (libm's powf does not and
// was a sixth of FLIP's time). Relative error below 1e-6, far under what FLIP's outputs resolve.
inline float fastExp2(float x) {
  // 2^x = 2^n * 2^f with n = round(x), f in [-0.5, 0.5]; 2^f = e^(f ln 2) by its Taylor series to
  // degree 7 (remainder < 1e-8).
  const float clamped = std::clamp(x, -126.0f, 127.0f);
  const float n = std::floor(clamped + 0.5f);
  const float t = (clamped - n) * 0.69314718f;
  float p = 1.0f / 5040.0f;
  p = p * t + 1.0f / 720.0f;
  p = p * t + 1.0f / 120.0f;
  p = p * t + 1.0f / 24.0f;
  p = p * t + 1.0f / 6.0f;
  p = p * t + 0.5f;
  p = p * t + 1.0f;
  p = p * t + 1.0f;
  const auto exponentBits = static_cast<uint32_t>(static_cast<int32_t>(n) + 127) << 23;
  float scaleBy;
  std::memcpy(&scaleBy, &exponentBits, sizeof scaleBy);
  return p * scaleBy;
}

inline float fastLog2(float x) {
  // x = m * 2^e with m in [sqrt(1/2), sqrt(2)); ln m = 2 atanh(s), s = (m-1)/(m+1), |s| < 0.172,
  // by its series to s^9 (remainder < 1e-9).
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int32_t e = static_cast<int32_t>((bits >> 23) & 0xffu) - 127;
  uint32_t mantissaBits = (bits & 0x7fffffu) | 0x3f800000u;  // m in [1, 2)
  float m;
  std::memcpy(&m, &mantissaBits, sizeof m);
  const bool upper = m > 1.41421356f;  // a select, not a branch: keeps the callers' loops vectorisable
  m = upper ? m * 0.5f : m;
  e += upper ? 1 : 0;
  const float s = (m - 1.0f) / (m + 1.0f);
  const float s2 = s * s;
  float series = 1.0f / 9.0f;
  series = series * s2 + 1.0f / 7.0f;
  series = series * s2 + 1.0f / 5.0f;
  series = series * s2 + 1.0f / 3.0f;
  series = series * s2 + 1.0f;
  return static_cast<float>(e) + 2.0f * s * series * 1.44269504f;  // ln -> log2
}

// x > 0 only; 0 otherwise.
inline float fastPow(float x, float e) { return x > 0.0f ? fastExp2(e * fastLog2(x)) : 0.0f; }

}  // namespace fgb::harness::flip_detail
