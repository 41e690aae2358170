// The FLIP colour model (private to the flip room): the paper's constants, the ACES tone curve, the
// colour-space conversions of the per-pixel loops and the CSF and feature kernels. The per-pixel
// helpers are FGB_INLINE so that each ISA variant of the engine compiles them with its own
// instructions (see flip_filters.hpp).
#pragma once

#include "flip_filters.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numbers>

namespace fgb::harness::flip_detail {

inline constexpr double kPi = std::numbers::pi;
// D65 reference white.
inline constexpr float kXn = 0.950428545f, kYn = 1.0f, kZn = 1.088900371f;
// Colour pipeline constants (paper, section 4).
inline constexpr double kColorExponent = 0.7;      // q_c
inline constexpr double kRedistributionPc = 0.4;   // p_c
inline constexpr double kRedistributionPt = 0.95;  // p_t
// Feature pipeline constants (paper, section 5).
inline constexpr double kFeatureExponent = 0.5;  // q_f

// ACES fit with the 0.6 pre-exposure folded into the coefficients: (k0 x^2 + k1 x) / (k3 x^2 + k4 x + k5).
inline constexpr double kAces0 = 0.6 * 0.6 * 2.51, kAces1 = 0.6 * 0.03, kAces3 = 0.6 * 0.6 * 2.43, kAces4 = 0.6 * 0.59,
                        kAces5 = 0.14;

// By value (std::clamp returns a reference, which keeps GCC from vectorising the loops using it).
FGB_INLINE float clamp01(float v) { return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v); }

// The same curve in float for the per-pixel loops, of an exposed value x >= 0 (or +inf). Inputs
// beyond 1e15 are clamped there (x^2 would overflow; the curve is 1 after clamping long before).
FGB_INLINE float acesCurveFloat(float x) {
  constexpr auto k0 = static_cast<float>(kAces0), k1 = static_cast<float>(kAces1), k3 = static_cast<float>(kAces3),
                 k4 = static_cast<float>(kAces4), k5 = static_cast<float>(kAces5);
  const float v = std::min(x, 1e15f);
  return clamp01((k0 * v * v + k1 * v) / (k3 * v * v + k4 * v + k5));
}

// max(0, v) for finite v; 0 for NaN and infinities. As comparisons, so that loops vectorise.
FGB_INLINE float nonNegativeFinite(float v) { return (v > 0.0f && v <= std::numeric_limits<float>::max()) ? v : 0.0f; }
// clamp(v, 0, 1) for finite v; 0 for NaN and infinities.
FGB_INLINE float unitFinite(float v) { return v <= std::numeric_limits<float>::max() ? clamp01(v) : 0.0f; }

// f(t) of CIE L*a*b*.
FGB_INLINE float labFunction(float t) {
  constexpr float delta = 6.0f / 29.0f;
  constexpr float threshold = delta * delta * delta;
  const float cube = fastCbrt(t);
  const float linear = t * (1.0f / (3.0f * delta * delta)) + 4.0f / 29.0f;
  return t > threshold ? cube : linear;
}

// The paper's error redistribution of the exponentiated HyAB distance: [0, p_c cmax) onto [0, p_t),
// [p_c cmax, cmax] onto [p_t, 1].
FGB_INLINE float redistributeColorError(float powered, float cmax) {
  const float knee = static_cast<float>(kRedistributionPc) * cmax;
  const auto pt = static_cast<float>(kRedistributionPt);
  const float below = pt / knee * powered;
  const float above = std::min(1.0f, pt + (powered - knee) / (cmax - knee) * (1.0f - pt));
  return powered < knee ? below : above;
}

// cmax: the (exponentiated) HyAB distance between Hunt-adjusted green and blue, the largest
// difference between two colours in the unit RGB cube.
float maxColorDifference();

// Filtered YCxCz -> linear RGB clamped to the unit cube -> Hunt-adjusted L*a*b*, for one row.
// The linear steps are folded into two 3x3 matrices (computed in double): YCxCz -> XYZ -> RGB, and
// RGB -> XYZ / white point; same matrices as xyzToLinearRgb / linearRgbToXyz.
struct PerceptualMatrices {
  std::array<float, 9> toRgb{};  // rows r, g, b; columns Y (normalised), Cx, Cz
  std::array<float, 9> toXyz{};  // rows X / Xn, Y / Yn, Z / Zn; columns r, g, b
};
constexpr PerceptualMatrices makePerceptualMatrices() {
  constexpr double fromXyz[9] = {3.24100323, -1.53739897, -0.49861588, -0.96922425, 1.87592998, 0.04155423,
                                 0.05563942, -0.20401121, 1.05714897};
  constexpr double toXyz[9] = {0.41238656, 0.35759149, 0.18045049, 0.21263682, 0.71518298, 0.07218020,
                               0.01933062, 0.11919716, 0.95037259};
  const double xn = static_cast<double>(kXn), yn = static_cast<double>(kYn), zn = static_cast<double>(kZn);
  PerceptualMatrices m;
  for (int row = 0; row < 3; ++row) {
    const double* c = fromXyz + 3 * row;
    // X = (y + cx / 500) Xn, Y = y Yn, Z = (y - cz / 200) Zn.
    m.toRgb[static_cast<std::size_t>(3 * row + 0)] = static_cast<float>(c[0] * xn + c[1] * yn + c[2] * zn);
    m.toRgb[static_cast<std::size_t>(3 * row + 1)] = static_cast<float>(c[0] * xn / 500.0);
    m.toRgb[static_cast<std::size_t>(3 * row + 2)] = static_cast<float>(-c[2] * zn / 200.0);
    const double white = row == 0 ? xn : (row == 1 ? yn : zn);
    for (int column = 0; column < 3; ++column) {
      m.toXyz[static_cast<std::size_t>(3 * row + column)] = static_cast<float>(toXyz[3 * row + column] / white);
    }
  }
  return m;
}
inline constexpr PerceptualMatrices kPerceptual = makePerceptualMatrices();

// The paper's filters, sampled for an observer of `ppd` pixels per degree.
struct Kernels {
  Kernel csfAchromatic, csfRedGreen, csfBlueYellow1, csfBlueYellow2;      // horizontal taps
  Kernel csfAchromaticV, csfRedGreenV, csfBlueYellow1V, csfBlueYellow2V;  // vertical taps
  Kernel gaussian, edge, point;                                           // feature kernels
};
Kernels makeKernels(double ppd);

}  // namespace fgb::harness::flip_detail
