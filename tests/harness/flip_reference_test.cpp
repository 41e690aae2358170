// Checks the fast FLIP (separable, trimmed and folded kernels, vectorised approximations of cbrt,
// pow and the sRGB curve) against a direct, double-precision evaluation of the paper's
// definitions with full 2D kernels, written independently here.
#include <fgb/harness/flip/flip.hpp>

#include "flip_filters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace fgb::harness {
namespace {

constexpr double kPi = std::numbers::pi;
using Plane = std::vector<double>;

struct Planar {
  int w = 0, h = 0;
  std::array<Plane, 3> c;  // linear RGB
};

Planar linearPlanes(const Image& image) {
  Planar p{static_cast<int>(image.width), static_cast<int>(image.height), {}};
  for (auto& plane : p.c) plane.resize(image.pixelCount());
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double v = std::clamp(static_cast<double>(image.rgba[i * 4 + k]), 0.0, 1.0);
      p.c[k][i] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    }
  }
  return p;
}

// Direct 2D convolution with replicated borders.
Plane convolve2d(const Plane& in, int w, int h, const std::vector<double>& kernel, int r) {
  Plane out(in.size(), 0.0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          const int sx = std::clamp(x + dx, 0, w - 1), sy = std::clamp(y + dy, 0, h - 1);
          sum += kernel[static_cast<std::size_t>((dy + r) * (2 * r + 1) + dx + r)] * in[static_cast<std::size_t>(sy * w + sx)];
        }
      }
      out[static_cast<std::size_t>(y * w + x)] = sum;
    }
  }
  return out;
}

std::array<double, 3> toXyz(double r, double g, double b) {
  return {0.4124564 * r + 0.3575761 * g + 0.1804375 * b, 0.2126729 * r + 0.7151522 * g + 0.0721750 * b,
          0.0193339 * r + 0.1191920 * g + 0.9503041 * b};
}
std::array<double, 3> toRgb(double x, double y, double z) {
  return {3.2404542 * x - 1.5371385 * y - 0.4985314 * z, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
          0.0556434 * x - 0.2040259 * y + 1.0572252 * z};
}
constexpr std::array<double, 3> kWhite{0.950428545, 1.0, 1.088900371};

std::array<double, 3> huntLab(double r, double g, double b) {
  const auto xyz = toXyz(r, g, b);
  auto f = [](double t) { return t > std::pow(6.0 / 29.0, 3) ? std::cbrt(t) : t / (3 * std::pow(6.0 / 29.0, 2)) + 4.0 / 29.0; };
  const double fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
  const double l = 116 * fy - 16;
  return {l, 0.01 * l * 500 * (fx - fy), 0.01 * l * 200 * (fy - fz)};
}

double hyab(const std::array<double, 3>& p, const std::array<double, 3>& q) {
  return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

struct Reference {
  double ppd;
  int csfRadius, featureRadius;
  std::array<std::vector<double>, 3> csf;
  std::vector<double> edgeX, edgeY, pointX, pointY;

  explicit Reference(double pixelsPerDegree) : ppd(pixelsPerDegree) {
    csfRadius = static_cast<int>(std::ceil(3 * std::sqrt(0.04 / (2 * kPi * kPi)) * ppd));
    const std::array<std::array<double, 4>, 3> params{{{1, 0.0047, 0, 1e-5}, {1, 0.0053, 0, 1e-5}, {34.1, 0.04, 13.5, 0.025}}};
    for (int c = 0; c < 3; ++c) {
      const auto [a1, b1, a2, b2] = params[static_cast<std::size_t>(c)];
      auto& k = csf[static_cast<std::size_t>(c)];
      double sum = 0;
      for (int y = -csfRadius; y <= csfRadius; ++y) {
        for (int x = -csfRadius; x <= csfRadius; ++x) {
          const double d2 = (x * x + y * y) / (ppd * ppd);
          k.push_back(a1 * std::sqrt(kPi / b1) * std::exp(-kPi * kPi * d2 / b1) + a2 * std::sqrt(kPi / b2) * std::exp(-kPi * kPi * d2 / b2));
          sum += k.back();
        }
      }
      for (double& v : k) v /= sum;
    }
    const double sd = 0.5 * 0.082 * ppd;
    featureRadius = static_cast<int>(std::ceil(3 * sd));
    auto make = [&](bool second, bool transpose) {
      std::vector<double> k;
      double pos = 0, neg = 0;
      for (int y = -featureRadius; y <= featureRadius; ++y) {
        for (int x = -featureRadius; x <= featureRadius; ++x) {
          const double u = transpose ? y : x;
          const double g = std::exp(-(x * x + y * y) / (2 * sd * sd));
          k.push_back(second ? (u * u / (sd * sd) - 1) * g : -u * g);
          (k.back() > 0 ? pos : neg) += k.back();
        }
      }
      for (double& v : k) v = v > 0 ? v / pos : v / -neg;
      return k;
    };
    edgeX = make(false, false);
    edgeY = make(false, true);
    pointX = make(true, false);
    pointY = make(true, true);
  }

  std::vector<double> flip(const Image& refImage, const Image& testImage) const {
    return flipLinear(linearPlanes(refImage), linearPlanes(testImage));
  }

  // FLIP of two linear display images in [0, 1].
  std::vector<double> flipLinear(const Planar& ref, const Planar& test) const {
    const int w = ref.w, h = ref.h;
    const std::size_t n = static_cast<std::size_t>(w * h);
    auto opponent = [&](const Planar& p) {
      std::array<Plane, 4> o;  // Y', Cx, Cz, normalised Y
      for (auto& plane : o) plane.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const auto xyz = toXyz(p.c[0][i], p.c[1][i], p.c[2][i]);
        const double yn = xyz[1] / kWhite[1];
        o[0][i] = 116 * yn - 16;
        o[1][i] = 500 * (xyz[0] / kWhite[0] - yn);
        o[2][i] = 200 * (yn - xyz[2] / kWhite[2]);
        o[3][i] = yn;
      }
      return o;
    };
    const auto ro = opponent(ref), to = opponent(test);
    std::array<Plane, 3> rf, tf;
    for (std::size_t c = 0; c < 3; ++c) {
      rf[c] = convolve2d(ro[c], w, h, csf[c], csfRadius);
      tf[c] = convolve2d(to[c], w, h, csf[c], csfRadius);
    }
    auto features = [&](const Plane& y) {
      const Plane ex = convolve2d(y, w, h, edgeX, featureRadius), ey = convolve2d(y, w, h, edgeY, featureRadius);
      const Plane px = convolve2d(y, w, h, pointX, featureRadius), py = convolve2d(y, w, h, pointY, featureRadius);
      std::pair<Plane, Plane> out{Plane(n), Plane(n)};
      for (std::size_t i = 0; i < n; ++i) {
        out.first[i] = std::hypot(ex[i], ey[i]);
        out.second[i] = std::hypot(px[i], py[i]);
      }
      return out;
    };
    const auto [re, rp] = features(ro[3]);
    const auto [te, tp] = features(to[3]);
    const double cmax = std::pow(hyab(huntLab(0, 1, 0), huntLab(0, 0, 1)), 0.7);
    std::vector<double> errors(n);
    for (std::size_t i = 0; i < n; ++i) {
      auto lab = [&](const std::array<Plane, 3>& f) {
        const double fy = (f[0][i] + 16) / 116;
        auto rgb = toRgb((fy + f[1][i] / 500) * kWhite[0], fy * kWhite[1], (fy - f[2][i] / 200) * kWhite[2]);
        for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
        return huntLab(rgb[0], rgb[1], rgb[2]);
      };
      const double powered = std::pow(hyab(lab(rf), lab(tf)), 0.7);
      const double knee = 0.4 * cmax;
      const double color = powered < knee ? 0.95 / knee * powered : 0.95 + (powered - knee) / (cmax - knee) * 0.05;
      const double feature = std::pow(std::max(std::abs(re[i] - te[i]), std::abs(rp[i] - tp[i])) / std::sqrt(2.0), 0.5);
      errors[i] = std::pow(color, 1 - feature);
    }
    return errors;
  }
};

Image scene(int w, int h, unsigned seed, double shift) {
  Image image = makeImage(static_cast<uint32_t>(w), static_cast<uint32_t>(h), Encoding::Srgb);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(0.0f, 0.15f);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float* p = &image.rgba[static_cast<std::size_t>(y * w + x) * 4];
      const bool disc = std::hypot(x - w / 2.0 - shift, y - h / 2.0) < h / 3.0;
      p[0] = disc ? 0.9f : 0.2f + noise(rng);
      p[1] = disc ? 0.3f : 0.5f;
      p[2] = static_cast<float>(x) / static_cast<float>(w);
      p[3] = 1.0f;
    }
  }
  return image;
}

TEST(FlipReference, FastImplementationMatchesDirectEvaluation) {
  for (double ppd : {defaultPixelsPerDegree(), 20.0}) {
    const Image a = scene(48, 40, 1, 0.0), b = scene(48, 40, 2, 2.5);
    const std::vector<double> expected = Reference(ppd).flip(a, b);
    const FlipMap fast = ldrFlip(a, b, ppd);
    double worst = 0.0, meanExpected = 0.0, meanFast = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      worst = std::max(worst, std::abs(expected[i] - fast.error[i]));
      meanExpected += expected[i];
      meanFast += fast.error[i];
    }
    EXPECT_LT(worst, 2e-3) << "ppd " << ppd;
    EXPECT_NEAR(meanFast / static_cast<double>(expected.size()), meanExpected / static_cast<double>(expected.size()), 1e-4);
    EXPECT_GT(meanExpected / static_cast<double>(expected.size()), 0.01);  // the pair does differ
  }
}

// The engine is compiled for several instruction sets; FGBENCH_FLIP_ISA caps the one it uses.
class IsaCap {
 public:
  explicit IsaCap(const char* isa) {
    if (isa) setenv("FGBENCH_FLIP_ISA", isa, 1);
  }
  ~IsaCap() { unsetenv("FGBENCH_FLIP_ISA"); }
  IsaCap(const IsaCap&) = delete;
  IsaCap& operator=(const IsaCap&) = delete;
};
constexpr std::array<const char*, 3> kIsas{"baseline", "avx2", nullptr};  // nullptr: the best the CPU has

// An HDR pair: the scene's colours scaled up to ~8x with a few bright spots, the test one changed.
Image hdrScene(int w, int h, unsigned seed, double shift) {
  Image image = scene(w, h, seed, shift);
  image.encoding = Encoding::Linear;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float* p = &image.rgba[static_cast<std::size_t>(y * w + x) * 4];
      const float gain = 0.25f + 8.0f * static_cast<float>(y) / static_cast<float>(h);
      for (int c = 0; c < 3; ++c) p[c] *= gain;
      if ((x * 7 + y * 3) % 97 == 0) p[0] = p[1] = p[2] = 40.0f;
    }
  }
  return image;
}

// HDR-FLIP as the paper defines it: the maximum over the exposures of LDR-FLIP of the ACES
// tone-mapped pair, evaluated directly (in double, with the public acesToneMap).
std::vector<double> referenceHdrFlip(const Image& a, const Image& b, double ppd) {
  const ExposureRange range = hdrExposureRange(a);
  const double step = (range.stop - range.start) / std::max(range.count - 1, 1);
  const Reference reference(ppd);
  std::vector<double> result(a.pixelCount(), 0.0);
  for (int i = 0; i < range.count; ++i) {
    const double exposure = range.start + i * step;
    auto toneMapped = [&](const Image& image) {
      Planar p{static_cast<int>(image.width), static_cast<int>(image.height), {}};
      for (auto& plane : p.c) plane.resize(image.pixelCount());
      for (std::size_t k = 0; k < image.pixelCount(); ++k) {
        for (int c = 0; c < 3; ++c) p.c[static_cast<std::size_t>(c)][k] = acesToneMap(image.rgba[k * 4 + static_cast<std::size_t>(c)], exposure);
      }
      return p;
    };
    const std::vector<double> errors = reference.flipLinear(toneMapped(a), toneMapped(b));
    for (std::size_t k = 0; k < errors.size(); ++k) result[k] = std::max(result[k], errors[k]);
  }
  return result;
}

void expectMatches(const std::vector<double>& expected, const std::vector<float>& actual, const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  double worst = 0.0, meanExpected = 0.0, meanActual = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    worst = std::max(worst, std::abs(expected[i] - actual[i]));
    meanExpected += expected[i];
    meanActual += actual[i];
  }
  meanExpected /= static_cast<double>(expected.size());
  meanActual /= static_cast<double>(expected.size());
  EXPECT_LT(worst, 2e-3) << what;
  EXPECT_NEAR(meanActual, meanExpected, 1e-4) << what;
  EXPECT_GT(meanExpected, 0.01) << what;  // the pair does differ
}

TEST(FlipReference, HdrFlipMatchesDirectEvaluationOnEveryIsa) {
  const Image a = hdrScene(48, 40, 1, 0.0), b = hdrScene(48, 40, 2, 2.5);
  const double ppd = defaultPixelsPerDegree();
  const std::vector<double> expected = referenceHdrFlip(a, b, ppd);
  for (const char* isa : kIsas) {
    const IsaCap cap(isa);
    const HdrFlipResult fast = hdrFlip(a, b, ppd);
    EXPECT_EQ(fast.exposures, hdrExposureRange(a).count);
    expectMatches(expected, fast.map.error, std::string("hdr, isa ") + (isa ? isa : "best"));
  }
}

// Wide and tall enough (at a small observer distance, so that the direct evaluation stays cheap)
// that the engine cuts the image into several strips and bands of rows.
TEST(FlipReference, TiledImagesMatchDirectEvaluationOnEveryIsa) {
  const double ppd = 12.0;
  const Image a = scene(300, 150, 3, 0.0), b = scene(300, 150, 4, 3.0);
  const std::vector<double> expected = Reference(ppd).flip(a, b);
  const Image ha = hdrScene(300, 150, 3, 0.0), hb = hdrScene(300, 150, 4, 3.0);
  const std::vector<double> expectedHdr = referenceHdrFlip(ha, hb, ppd);
  for (const char* isa : kIsas) {
    const IsaCap cap(isa);
    const std::string name = isa ? isa : "best";
    expectMatches(expected, ldrFlip(a, b, ppd).error, "ldr, isa " + name);
    expectMatches(expectedHdr, hdrFlip(ha, hb, ppd).map.error, "hdr, isa " + name);
  }
}

TEST(FlipReference, InstructionSetsAgree) {
  const Image a = hdrScene(200, 70, 5, 0.0), b = hdrScene(200, 70, 6, 1.5);
  std::vector<std::vector<float>> maps;
  for (const char* isa : kIsas) {
    const IsaCap cap(isa);
    maps.push_back(hdrFlip(a, b).map.error);
  }
  // The same arithmetic up to rounding (FMA contraction, vector widths). Where two colours are
  // nearly equal, their HyAB distance is at the rounding noise of L*a*b* (~1e-5 of L = 50) and the
  // error there, ~1e-4, is noise too: bound the worst pixel loosely and the mean tightly.
  for (std::size_t m = 1; m < maps.size(); ++m) {
    float worst = 0.0f;
    double sumDifference = 0.0;
    for (std::size_t i = 0; i < maps[0].size(); ++i) {
      worst = std::max(worst, std::abs(maps[m][i] - maps[0][i]));
      sumDifference += static_cast<double>(maps[m][i]) - static_cast<double>(maps[0][i]);
    }
    EXPECT_LT(worst, 5e-4f) << "isa " << m;
    EXPECT_LT(std::abs(sumDifference) / static_cast<double>(maps[0].size()), 1e-6) << "isa " << m;
  }
}

TEST(FlipReference, FastMathApproximationsAreAccurate) {
  for (float x = 1e-6f; x < 1e4f; x *= 1.37f) {
    EXPECT_NEAR(flip_detail::fastLog2(x), std::log2(x), 2e-6f * std::max(1.0f, std::abs(std::log2(x))));
    for (float e : {0.3f, 0.7f, 1.0f}) EXPECT_NEAR(flip_detail::fastPow(x, e), std::pow(x, e), 3e-6f * std::pow(x, e)) << x << "^" << e;
  }
  for (float x = -20.0f; x < 20.0f; x += 0.173f) EXPECT_NEAR(flip_detail::fastExp2(x), std::exp2(x), 2e-6f * std::exp2(x));
  EXPECT_EQ(flip_detail::fastPow(0.0f, 0.7f), 0.0f);
  for (float x = 1e-7f; x < 1e3f; x *= 1.0013f) EXPECT_NEAR(flip_detail::fastCbrt(x), std::cbrt(x), 3e-7f * std::cbrt(x)) << x;
}

}  // namespace
}  // namespace fgb::harness
