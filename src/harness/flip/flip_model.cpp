// The FLIP colour model's one-off parts: cmax from the reference (scalar) Hunt-adjusted L*a*b*, and
// the CSF and feature kernels sampled for an observer.
#include "flip_model.hpp"

#include <array>
#include <cmath>

namespace fgb::harness::flip_detail {
namespace {

constexpr double kEdgeWidthDegrees = 0.082;  // w: peak-to-trough of the human edge detector
// Spatial CSFs per channel (a1, b1, a2, b2): achromatic, red-green, blue-yellow.
struct CsfParameters {
  double a1, b1, a2, b2;
};
constexpr CsfParameters kCsfAchromatic{1.0, 0.0047, 0.0, 1e-5};
constexpr CsfParameters kCsfRedGreen{1.0, 0.0053, 0.0, 1e-5};
constexpr CsfParameters kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};
constexpr double kLargestCsfScale = 0.04;  // max over every b: sets the common filter radius

struct Rgb {
  float r, g, b;
};
struct Xyz {
  float x, y, z;
};

Xyz linearRgbToXyz(Rgb c) {
  return {0.41238656f * c.r + 0.35759149f * c.g + 0.18045049f * c.b,
          0.21263682f * c.r + 0.71518298f * c.g + 0.07218020f * c.b,
          0.01933062f * c.r + 0.11919716f * c.g + 0.95037259f * c.b};
}

float labF(float t) {
  constexpr float delta = 6.0f / 29.0f;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
}

// Hunt-adjusted CIE L*a*b*: chroma scaled by 0.01 L so dark colours differ less.
std::array<float, 3> huntLab(Rgb linear) {
  const Xyz xyz = linearRgbToXyz(linear);
  const float fx = labF(xyz.x / kXn), fy = labF(xyz.y / kYn), fz = labF(xyz.z / kZn);
  const float l = 116.0f * fy - 16.0f;
  return {l, 0.01f * l * 500.0f * (fx - fy), 0.01f * l * 200.0f * (fy - fz)};
}

float hyab(const std::array<float, 3>& p, const std::array<float, 3>& q) {
  const float da = p[1] - q[1], db = p[2] - q[2];
  return std::abs(p[0] - q[0]) + std::sqrt(da * da + db * db);
}

// The CSF a1 sqrt(pi/b1) exp(-pi^2 r^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2/b2), normalised to sum 1
// in 2D, as a sum of separable terms: term k is (h_k along x) then (v_k along y).
void csfKernels(const CsfParameters& p, int radius, double ppd, Kernel& h1, Kernel& v1, Kernel& h2, Kernel& v2) {
  auto gaussian = [&](double b) {
    return sampleKernel(radius, [&](double i) { return std::exp(-kPi * kPi * (i / ppd) * (i / ppd) / b); });
  };
  v1 = gaussian(p.b1);
  v2 = gaussian(p.b2);
  const double c1 = p.a1 * std::sqrt(kPi / p.b1), c2 = p.a2 * std::sqrt(kPi / p.b2);
  const double s1 = sumOf(v1), s2 = sumOf(v2);
  const double total = c1 * s1 * s1 + c2 * s2 * s2;
  h1 = v1;
  scale(h1, c1 / total);
  h2 = v2;
  scale(h2, c2 / total);
}

}  // namespace

float maxColorDifference() {
  static const float cmax = static_cast<float>(std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kColorExponent));
  return cmax;
}

Kernels makeKernels(double ppd) {
  Kernels k;
  const int csfRadius = static_cast<int>(std::ceil(3.0 * std::sqrt(kLargestCsfScale / (2.0 * kPi * kPi)) * ppd));
  Kernel unusedH, unusedV;  // a2 = 0 for the achromatic and red-green CSFs
  csfKernels(kCsfAchromatic, csfRadius, ppd, k.csfAchromatic, k.csfAchromaticV, unusedH, unusedV);
  csfKernels(kCsfRedGreen, csfRadius, ppd, k.csfRedGreen, k.csfRedGreenV, unusedH, unusedV);
  csfKernels(kCsfBlueYellow, csfRadius, ppd, k.csfBlueYellow1, k.csfBlueYellow1V, k.csfBlueYellow2, k.csfBlueYellow2V);

  const double sd = 0.5 * kEdgeWidthDegrees * ppd;
  const int featureRadius = static_cast<int>(std::ceil(3.0 * sd));
  auto g = [sd](double x) { return std::exp(-x * x / (2.0 * sd * sd)); };
  k.gaussian = sampleKernel(featureRadius, g);
  scale(k.gaussian, 1.0 / sumOf(k.gaussian));
  // 2D kernels d(x) g(y): normalising the 1D parts (signed parts of d to +-1, g to 1) normalises
  // the 2D kernel's positive and negative weights to +-1, as the paper specifies.
  k.edge = sampleKernel(featureRadius, [&](double x) { return -x * g(x); });
  normalizeSignedParts(k.edge);
  k.point = sampleKernel(featureRadius, [&](double x) { return (x * x / (sd * sd) - 1.0) * g(x); });
  normalizeSignedParts(k.point);
  // The narrow achromatic and red-green CSFs share the blue-yellow one's radius on paper; their
  // outer taps are ~1e-10 and only cost time.
  constexpr double kNegligibleTap = 1e-9;
  for (Kernel* kernel : {&k.csfAchromatic, &k.csfAchromaticV, &k.csfRedGreen, &k.csfRedGreenV, &k.csfBlueYellow1,
                         &k.csfBlueYellow1V, &k.csfBlueYellow2, &k.csfBlueYellow2V}) {
    trimNegligibleTaps(*kernel, kNegligibleTap);
  }
  for (Kernel* kernel : {&k.csfAchromatic, &k.csfAchromaticV, &k.csfRedGreen, &k.csfRedGreenV, &k.csfBlueYellow1,
                         &k.csfBlueYellow1V, &k.csfBlueYellow2, &k.csfBlueYellow2V, &k.gaussian, &k.edge, &k.point}) {
    detectSymmetry(*kernel);
  }
  return k;
}

}  // namespace fgb::harness::flip_detail
