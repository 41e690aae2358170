// FLIP, following the structure of the paper: a colour pipeline (opponent space, contrast
// sensitivity filtering, Hunt-adjusted L*a*b*, HyAB distance, error redistribution) and a feature
// pipeline (edges and points on luminance), combined as dE_c^(1 - dE_f).
// Speed: all filters are separable (the blue-yellow CSF is a sum of two separable Gaussians); the
// horizontal passes write planes, the vertical passes are fused with the per-pixel error, and rows
// are spread over threads.
#include <fgb/harness/flip.hpp>

#include <fgb/harness/parallel.hpp>

#include "flip_filters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <numbers>
#include <stdexcept>

namespace fgb::harness {
namespace {

using flip_detail::Kernel;

constexpr double kPi = std::numbers::pi;
// D65 reference white.
constexpr float kXn = 0.950428545f, kYn = 1.0f, kZn = 1.088900371f;
// Colour pipeline constants (paper, section 4).
constexpr double kColorExponent = 0.7;     // q_c
constexpr double kRedistributionPc = 0.4;  // p_c
constexpr double kRedistributionPt = 0.95; // p_t
// Feature pipeline constants (paper, section 5).
constexpr double kFeatureExponent = 0.5;  // q_f
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


// By value (std::clamp returns a reference, which keeps GCC from vectorising the loops using it).
inline float clamp01(float v) { return v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v); }

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

// cmax: the (exponentiated) HyAB distance between Hunt-adjusted green and blue, the largest
// difference between two colours in the unit RGB cube.
float maxColorDifference() {
  static const float cmax = static_cast<float>(
      std::pow(hyab(huntLab({0, 1, 0}), huntLab({0, 0, 1})), kColorExponent));
  return cmax;
}

float redistributeColorError(float powered, float cmax) {
  const float knee = static_cast<float>(kRedistributionPc) * cmax;
  const auto pt = static_cast<float>(kRedistributionPt);
  const float below = pt / knee * powered;
  const float above = std::min(1.0f, pt + (powered - knee) / (cmax - knee) * (1.0f - pt));
  return powered < knee ? below : above;
}

struct Kernels {
  Kernel csfAchromatic, csfRedGreen, csfBlueYellow1, csfBlueYellow2;  // horizontal taps
  Kernel csfAchromaticV, csfRedGreenV, csfBlueYellow1V, csfBlueYellow2V;  // vertical taps
  Kernel gaussian, edge, point;  // feature kernels
};

// The CSF a1 sqrt(pi/b1) exp(-pi^2 r^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 r^2/b2), normalised to sum 1
// in 2D, as a sum of separable terms: term k is (h_k along x) then (v_k along y).
void csfKernels(const CsfParameters& p, int radius, double ppd, Kernel& h1, Kernel& v1, Kernel& h2, Kernel& v2) {
  auto gaussian = [&](double b) {
    return flip_detail::sampleKernel(radius, [&](double i) { return std::exp(-kPi * kPi * (i / ppd) * (i / ppd) / b); });
  };
  v1 = gaussian(p.b1);
  v2 = gaussian(p.b2);
  const double c1 = p.a1 * std::sqrt(kPi / p.b1), c2 = p.a2 * std::sqrt(kPi / p.b2);
  const double s1 = flip_detail::sumOf(v1), s2 = flip_detail::sumOf(v2);
  const double total = c1 * s1 * s1 + c2 * s2 * s2;
  h1 = v1;
  flip_detail::scale(h1, c1 / total);
  h2 = v2;
  flip_detail::scale(h2, c2 / total);
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
  k.gaussian = flip_detail::sampleKernel(featureRadius, g);
  flip_detail::scale(k.gaussian, 1.0 / flip_detail::sumOf(k.gaussian));
  // 2D kernels d(x) g(y): normalising the 1D parts (signed parts of d to +-1, g to 1) normalises
  // the 2D kernel's positive and negative weights to +-1, as the paper specifies.
  k.edge = flip_detail::sampleKernel(featureRadius, [&](double x) { return -x * g(x); });
  flip_detail::normalizeSignedParts(k.edge);
  k.point = flip_detail::sampleKernel(featureRadius, [&](double x) { return (x * x / (sd * sd) - 1.0) * g(x); });
  flip_detail::normalizeSignedParts(k.point);
  // The narrow achromatic and red-green CSFs share the blue-yellow one's radius on paper; their
  // outer taps are ~1e-10 and only cost time.
  constexpr double kNegligibleTap = 1e-9;
  for (Kernel* kernel : {&k.csfAchromatic, &k.csfAchromaticV, &k.csfRedGreen, &k.csfRedGreenV, &k.csfBlueYellow1,
                         &k.csfBlueYellow1V, &k.csfBlueYellow2, &k.csfBlueYellow2V}) {
    flip_detail::trimNegligibleTaps(*kernel, kNegligibleTap);
  }
  for (Kernel* kernel : {&k.csfAchromatic, &k.csfAchromaticV, &k.csfRedGreen, &k.csfRedGreenV, &k.csfBlueYellow1,
                         &k.csfBlueYellow1V, &k.csfBlueYellow2, &k.csfBlueYellow2V, &k.gaussian, &k.edge, &k.point}) {
    flip_detail::detectSymmetry(*kernel);
  }
  return k;
}

// The seven horizontally filtered planes of one image.
struct FilteredPlanes {
  enum Index { Achromatic, RedGreen, BlueYellow1, BlueYellow2, FeatureGauss, FeatureEdge, FeaturePoint, Count };
  std::array<std::vector<float>, Count> planes;
};

// Fills one row of linear RGB in [0, 1] (display images, or tone-mapped HDR), planar.
using LinearSource = std::function<void(std::size_t row, float* r, float* g, float* b)>;

void horizontalPasses(const LinearSource& source, uint32_t width, uint32_t height, const Kernels& k, FilteredPlanes& out) {
  for (auto& plane : out.planes) plane.resize(static_cast<std::size_t>(width) * height);
  parallelFor(height, 8, [&](std::size_t begin, std::size_t end) {
    std::vector<float> r(width), g(width), b(width), y(width), cx(width), cz(width), luminance(width), scratch;
    for (std::size_t row = begin; row < end; ++row) {
      const std::size_t base = row * width;
      source(row, r.data(), g.data(), b.data());
      for (uint32_t x = 0; x < width; ++x) {
        const Xyz c = linearRgbToXyz({r[x], g[x], b[x]});
        const float yn = c.y / kYn;
        y[x] = 116.0f * yn - 16.0f;
        cx[x] = 500.0f * (c.x / kXn - yn);
        cz[x] = 200.0f * (yn - c.z / kZn);
        luminance[x] = yn;  // (Y + 16) / 116 of YCxCz: normalised luminance for the features
      }
      auto at = [&](FilteredPlanes::Index i) { return out.planes[i].data() + base; };
      flip_detail::convolveRow(y.data(), at(FilteredPlanes::Achromatic), width, k.csfAchromatic, scratch);
      flip_detail::convolveRow(cx.data(), at(FilteredPlanes::RedGreen), width, k.csfRedGreen, scratch);
      flip_detail::convolveRow(cz.data(), at(FilteredPlanes::BlueYellow1), width, k.csfBlueYellow1, scratch);
      flip_detail::convolveRow(cz.data(), at(FilteredPlanes::BlueYellow2), width, k.csfBlueYellow2, scratch);
      flip_detail::convolveRow(luminance.data(), at(FilteredPlanes::FeatureGauss), width, k.gaussian, scratch);
      flip_detail::convolveRow(luminance.data(), at(FilteredPlanes::FeatureEdge), width, k.edge, scratch);
      flip_detail::convolveRow(luminance.data(), at(FilteredPlanes::FeaturePoint), width, k.point, scratch);
    }
  });
}

// Vertical passes for one row of one image: filtered opponent colour and feature magnitudes.
struct RowResult {
  std::vector<float> y, cx, cz, edge, point, tmpA, tmpB;
  explicit RowResult(uint32_t width) : y(width), cx(width), cz(width), edge(width), point(width), tmpA(width), tmpB(width) {}
};

void verticalPasses(const FilteredPlanes& in, uint32_t width, uint32_t height, uint32_t row, uint32_t x0, uint32_t count,
                    const Kernels& k, RowResult& r) {
  auto plane = [&](FilteredPlanes::Index i) { return in.planes[i].data(); };
  flip_detail::convolveColumnRow(plane(FilteredPlanes::Achromatic), width, height, row, x0, count, k.csfAchromaticV, r.y.data());
  flip_detail::convolveColumnRow(plane(FilteredPlanes::RedGreen), width, height, row, x0, count, k.csfRedGreenV, r.cx.data());
  flip_detail::convolveColumnRow(plane(FilteredPlanes::BlueYellow1), width, height, row, x0, count, k.csfBlueYellow1V, r.cz.data());
  flip_detail::convolveColumnRow(plane(FilteredPlanes::BlueYellow2), width, height, row, x0, count, k.csfBlueYellow2V, r.tmpA.data());
  for (uint32_t x = 0; x < count; ++x) r.cz[x] += r.tmpA[x];
  // Edges: d(x) g(y) and g(x) d(y); points: p(x) g(y) and g(x) p(y).
  flip_detail::convolveColumnRow(plane(FilteredPlanes::FeatureEdge), width, height, row, x0, count, k.gaussian, r.tmpA.data());
  flip_detail::convolveColumnRow(plane(FilteredPlanes::FeatureGauss), width, height, row, x0, count, k.edge, r.tmpB.data());
  for (uint32_t x = 0; x < count; ++x) r.edge[x] = std::sqrt(r.tmpA[x] * r.tmpA[x] + r.tmpB[x] * r.tmpB[x]);
  flip_detail::convolveColumnRow(plane(FilteredPlanes::FeaturePoint), width, height, row, x0, count, k.gaussian, r.tmpA.data());
  flip_detail::convolveColumnRow(plane(FilteredPlanes::FeatureGauss), width, height, row, x0, count, k.point, r.tmpB.data());
  for (uint32_t x = 0; x < count; ++x) r.point[x] = std::sqrt(r.tmpA[x] * r.tmpA[x] + r.tmpB[x] * r.tmpB[x]);
}

// Cube root for the L*a*b* transform: exponent-third bit trick, then two Halley steps (cubic
// convergence: ~1e-12 relative, below float precision). Branch-free so the row loops vectorise;
// the libm call was a tenth of FLIP's time. Inputs <= 0 give a small positive number, which the
// caller never selects (L*a*b* uses the linear segment there).
inline float fastCbrt(float x) {
  const float v = std::max(x, 1e-30f);
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  bits = bits / 3u + 709921077u;  // ~ (127 - 127/3) << 23: a first guess within a few percent
  float y;
  std::memcpy(&y, &bits, sizeof y);
  for (int i = 0; i < 2; ++i) {
    const float y3 = y * y * y;
    y = y * (y3 + 2.0f * v) / (2.0f * y3 + v);
  }
  return y;
}

// f(t) of CIE L*a*b*, in place over n values.
FGB_VECTOR_CLONES
void labFunctionInPlace(float* t, uint32_t n) {
  constexpr float delta = 6.0f / 29.0f;
  constexpr float threshold = delta * delta * delta;
  for (uint32_t i = 0; i < n; ++i) {
    const float cube = fastCbrt(t[i]);
    const float linear = t[i] / (3.0f * delta * delta) + 4.0f / 29.0f;
    t[i] = t[i] > threshold ? cube : linear;
  }
}

// Filtered YCxCz -> linear RGB clamped to the unit cube -> Hunt-adjusted L*a*b*, for a row.
// Written as simple loops over arrays so that each one vectorises.
FGB_VECTOR_CLONES
void perceptualRow(const RowResult& in, uint32_t width, float* outL, float* outA, float* outB) {
  // Plain restrict pointers: through the vectors the compiler must assume the outputs alias them.
  const float* __restrict y = in.y.data();
  const float* __restrict cx = in.cx.data();
  const float* __restrict cz = in.cz.data();
  float* __restrict fx = outA;  // the outputs double as scratch for f(X/Xn), f(Y/Yn), f(Z/Zn)
  float* __restrict fy = outL;
  float* __restrict fz = outB;
  for (uint32_t x = 0; x < width; ++x) {
    const float yy = (y[x] + 16.0f) / 116.0f;
    const float X = (yy + cx[x] / 500.0f) * kXn, Y = yy * kYn, Z = (yy - cz[x] / 200.0f) * kZn;
    // Same matrices as xyzToLinearRgb / linearRgbToXyz, spelled out so the loop vectorises.
    const float r = clamp01(3.24100323f * X - 1.53739897f * Y - 0.49861588f * Z);
    const float g = clamp01(-0.96922425f * X + 1.87592998f * Y + 0.04155423f * Z);
    const float b = clamp01(0.05563942f * X - 0.20401121f * Y + 1.05714897f * Z);
    fx[x] = (0.41238656f * r + 0.35759149f * g + 0.18045049f * b) / kXn;
    fy[x] = (0.21263682f * r + 0.71518298f * g + 0.07218020f * b) / kYn;
    fz[x] = (0.01933062f * r + 0.11919716f * g + 0.95037259f * b) / kZn;
  }
  labFunctionInPlace(fx, width);
  labFunctionInPlace(fy, width);
  labFunctionInPlace(fz, width);
  for (uint32_t x = 0; x < width; ++x) {
    const float l = 116.0f * fy[x] - 16.0f;
    const float a = 0.01f * l * 500.0f * (fx[x] - fy[x]);
    const float b = 0.01f * l * 200.0f * (fy[x] - fz[x]);
    fy[x] = l;
    fx[x] = a;
    fz[x] = b;
  }
}

struct CombineScratch {
  std::vector<float> refL, refA, refB, testL, testA, testB;
  explicit CombineScratch(uint32_t width)
      : refL(width), refA(width), refB(width), testL(width), testA(width), testB(width) {}
};

// HyAB colour error, redistributed; feature error; combined dE_c^(1 - dE_f).
FGB_VECTOR_CLONES
void errorRow(const RowResult& ref, const RowResult& test, const CombineScratch& s, uint32_t width, float cmax, float* out) {
  const auto qc = static_cast<float>(kColorExponent);
  static_assert(kFeatureExponent == 0.5, "the feature exponent is applied as a square root");
  const float* __restrict rl = s.refL.data();
  const float* __restrict ra = s.refA.data();
  const float* __restrict rb = s.refB.data();
  const float* __restrict tl = s.testL.data();
  const float* __restrict ta = s.testA.data();
  const float* __restrict tb = s.testB.data();
  const float* __restrict re = ref.edge.data();
  const float* __restrict rp = ref.point.data();
  const float* __restrict te = test.edge.data();
  const float* __restrict tp = test.point.data();
  float* __restrict o = out;
  for (uint32_t x = 0; x < width; ++x) {
    const float da = ra[x] - ta[x], db = rb[x] - tb[x];
    const float hy = std::abs(rl[x] - tl[x]) + std::sqrt(da * da + db * db);
    const float colorError = redistributeColorError(flip_detail::fastPow(hy, qc), cmax);
    const float featureDifference = std::max(std::abs(re[x] - te[x]), std::abs(rp[x] - tp[x]));
    const float featureError = std::clamp(std::sqrt(featureDifference / std::numbers::sqrt2_v<float>), 0.0f, 1.0f);
    o[x] = std::min(1.0f, flip_detail::fastPow(colorError, 1.0f - featureError));
  }
}

void combineRow(const RowResult& ref, const RowResult& test, uint32_t width, float cmax, CombineScratch& s, float* out) {
  perceptualRow(ref, width, s.refL.data(), s.refA.data(), s.refB.data());
  perceptualRow(test, width, s.testL.data(), s.testA.data(), s.testB.data());
  errorRow(ref, test, s, width, cmax, out);
}

// Planes reused across HDR-FLIP's exposures: allocating 14 fresh full-size planes per exposure
// cost more in page faults than some of the filters.
struct FlipWorkspace {
  FilteredPlanes reference, test;
};

FlipMap flipFromSources(const LinearSource& reference, const LinearSource& test, uint32_t width, uint32_t height, double ppd,
                        FlipWorkspace& workspace) {
  const Kernels kernels = makeKernels(ppd);
  FilteredPlanes& ref = workspace.reference;
  FilteredPlanes& tst = workspace.test;
  horizontalPasses(reference, width, height, kernels, ref);
  horizontalPasses(test, width, height, kernels, tst);
  FlipMap map{width, height, std::vector<float>(static_cast<std::size_t>(width) * height)};
  const float cmax = maxColorDifference();
  // Column blocks walked top to bottom: consecutive rows share all but one of the rows each
  // vertical tap reads, so those stay in cache instead of streaming 14 planes per output row.
  constexpr uint32_t kColumnBlock = 256;
  parallelFor(height, 8, [&](std::size_t begin, std::size_t end) {
    RowResult r(kColumnBlock), t(kColumnBlock);
    CombineScratch scratch(kColumnBlock);
    for (uint32_t x0 = 0; x0 < width; x0 += kColumnBlock) {
      const uint32_t count = std::min(kColumnBlock, width - x0);
      for (std::size_t row = begin; row < end; ++row) {
        const auto y = static_cast<uint32_t>(row);
        verticalPasses(ref, width, height, y, x0, count, kernels, r);
        verticalPasses(tst, width, height, y, x0, count, kernels, t);
        combineRow(r, t, count, cmax, scratch, map.error.data() + row * width + x0);
      }
    }
  });
  return map;
}

void requireSameSize(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument("FLIP: image sizes differ (" + describeSize(a) + " vs " + describeSize(b) + ")");
  }
  if (a.width == 0 || a.height == 0) throw std::invalid_argument("FLIP: empty image");
}

float finiteOrZero(float v) { return std::isfinite(v) ? v : 0.0f; }

// sRGB decoding by table with linear interpolation (error < 1e-6): the exact curve's powf per
// channel dominated LDR-FLIP's colour conversion.
class SrgbDecoder {
 public:
  SrgbDecoder() {
    for (int i = 0; i <= kSteps; ++i) table_[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<float>(i) / kSteps);
  }
  float operator()(float encoded) const {
    const float position = std::clamp(encoded, 0.0f, 1.0f) * kSteps;
    const int i = std::min(static_cast<int>(position), kSteps - 1);
    const float f = position - static_cast<float>(i);
    return table_[static_cast<std::size_t>(i)] + f * (table_[static_cast<std::size_t>(i) + 1] - table_[static_cast<std::size_t>(i)]);
  }

 private:
  static constexpr int kSteps = 4096;
  std::array<float, kSteps + 1> table_{};
};

LinearSource displaySource(const Image& image) {
  const bool srgb = image.encoding == Encoding::Srgb;
  const float* p = image.rgba.data();
  const uint32_t width = image.width;
  static const SrgbDecoder decode;
  return [p, srgb, width](std::size_t row, float* r, float* g, float* b) {
    const float* px = p + row * width * 4;
    for (uint32_t x = 0; x < width; ++x, px += 4) {
      float* out[3] = {r + x, g + x, b + x};
      for (int c = 0; c < 3; ++c) {
        const float v = std::clamp(finiteOrZero(px[c]), 0.0f, 1.0f);
        *out[c] = srgb ? decode(v) : v;
      }
    }
  };
}

// ACES fit with the 0.6 pre-exposure folded into the coefficients: (k0 x^2 + k1 x) / (k3 x^2 + k4 x + k5).
constexpr double kAces0 = 0.6 * 0.6 * 2.51, kAces1 = 0.6 * 0.03, kAces3 = 0.6 * 0.6 * 2.43, kAces4 = 0.6 * 0.59, kAces5 = 0.14;

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

// The same curve in float for the per-pixel loops; large inputs saturate to 1 like the double one.
float acesCurveFloat(float x) {
  constexpr auto k0 = static_cast<float>(kAces0), k1 = static_cast<float>(kAces1), k3 = static_cast<float>(kAces3),
                 k4 = static_cast<float>(kAces4), k5 = static_cast<float>(kAces5);
  if (x > 1e15f) return 1.0f;  // x^2 would overflow; the curve is 1 after clamping long before
  return std::clamp((k0 * x * x + k1 * x) / (k3 * x * x + k4 * x + k5), 0.0f, 1.0f);
}

float luminance(const float* p) { return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]; }

}  // namespace

double defaultPixelsPerDegree() { return 0.7 * 3840.0 / 0.7 * kPi / 180.0; }

FlipMap ldrFlip(const Image& reference, const Image& test, double pixelsPerDegree) {
  requireSameSize(reference, test);
  FlipWorkspace workspace;
  return flipFromSources(displaySource(reference), displaySource(test), reference.width, reference.height, pixelsPerDegree,
                         workspace);
}

float acesToneMap(float value, double exposure) {
  return acesCurve(std::max(0.0, static_cast<double>(finiteOrZero(value))) * std::exp2(exposure));
}

ExposureRange hdrExposureRange(const Image& linearReference) {
  constexpr double kTarget = 0.85;  // tone-mapped value the extreme luminances are mapped to
  std::vector<float> lum(linearReference.pixelCount());
  for (std::size_t i = 0; i < lum.size(); ++i) lum[i] = std::max(0.0f, finiteOrZero(luminance(&linearReference.rgba[i * 4])));
  ExposureRange range;
  if (lum.empty()) return range;
  const float yMax = *std::max_element(lum.begin(), lum.end());
  if (yMax <= 0.0f) return range;
  auto middle = lum.begin() + static_cast<std::ptrdiff_t>(lum.size() / 2);
  std::nth_element(lum.begin(), middle, lum.end());
  float yMedian = *middle;
  if (yMedian <= 0.0f) {
    // A mostly black image: use the darkest lit pixel so the range still reaches the shadows.
    float smallest = yMax;
    for (float v : lum) if (v > 0.0f) smallest = std::min(smallest, v);
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
  FlipWorkspace workspace;
  for (int i = 0; i < range.count; ++i) {
    const double exposure = range.start + i * step;
    const double scaleFactor = std::exp2(exposure);
    const auto exposureScale = static_cast<float>(scaleFactor);
    auto toneMapped = [exposureScale](const Image& image) -> LinearSource {
      const float* p = image.rgba.data();
      const uint32_t width = image.width;
      return [p, exposureScale, width](std::size_t row, float* r, float* g, float* b) {
        const float* px = p + row * width * 4;
        for (uint32_t x = 0; x < width; ++x, px += 4) {
          r[x] = acesCurveFloat(std::max(0.0f, finiteOrZero(px[0])) * exposureScale);
          g[x] = acesCurveFloat(std::max(0.0f, finiteOrZero(px[1])) * exposureScale);
          b[x] = acesCurveFloat(std::max(0.0f, finiteOrZero(px[2])) * exposureScale);
        }
      };
    };
    FlipMap map = flipFromSources(toneMapped(reference), toneMapped(test), reference.width, reference.height, pixelsPerDegree,
                                  workspace);
    if (i == 0) {
      result.map = std::move(map);
    } else {
      for (std::size_t k = 0; k < map.error.size(); ++k) result.map.error[k] = std::max(result.map.error[k], map.error[k]);
    }
  }
  return result;
}

}  // namespace fgb::harness
