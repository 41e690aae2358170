// FLIP is tested on properties the paper's definition guarantees, not on magic numbers.
#include <fgb/harness/flip/flip.hpp>
#include <fgb/harness/metrics/metrics.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace fgb::harness {
namespace {

Image texture(uint32_t w, uint32_t h, Encoding e, unsigned seed) {
  Image image = makeImage(w, h, e);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> noise(0.0f, 0.2f);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      float* p = &image.rgba[(static_cast<std::size_t>(y) * w + x) * 4];
      p[0] = 0.4f + 0.3f * std::sin(x * 0.2f) + noise(rng);
      p[1] = 0.4f + 0.3f * std::cos(y * 0.15f);
      p[2] = ((x / 8 + y / 8) % 2) ? 0.8f : 0.2f;
      p[3] = 1.0f;
    }
  }
  return image;
}

double meanOf(const FlipMap& m) {
  return std::accumulate(m.error.begin(), m.error.end(), 0.0) / static_cast<double>(m.error.size());
}

// Adds `amount` to every channel in the central square.
Image perturbed(const Image& base, float amount) {
  Image out = base;
  for (uint32_t y = base.height / 4; y < 3 * base.height / 4; ++y) {
    for (uint32_t x = base.width / 4; x < 3 * base.width / 4; ++x) {
      float* p = &out.rgba[(static_cast<std::size_t>(y) * base.width + x) * 4];
      for (int c = 0; c < 3; ++c) p[c] = std::clamp(p[c] + amount, 0.0f, 1.0f);
    }
  }
  return out;
}

TEST(Flip, IdenticalImagesGiveZeroEverywhere) {
  const Image a = texture(64, 48, Encoding::Srgb, 1);
  const FlipMap m = ldrFlip(a, a);
  ASSERT_EQ(m.error.size(), 64u * 48u);
  EXPECT_EQ(*std::max_element(m.error.begin(), m.error.end()), 0.0f);
}

TEST(Flip, ErrorsAreBoundedInUnitInterval) {
  const Image a = texture(64, 48, Encoding::Srgb, 1);
  const Image b = texture(64, 48, Encoding::Srgb, 2);
  const Image black = makeImage(64, 48, Encoding::Srgb);
  for (const auto& [ref, test] : {std::pair{&a, &b}, std::pair{&a, &black}}) {
    const FlipMap m = ldrFlip(*ref, *test);
    for (float e : m.error) {
      ASSERT_GE(e, 0.0f);
      ASSERT_LE(e, 1.0f);
    }
  }
}

TEST(Flip, MonotoneInPerturbationSize) {
  const Image base = texture(96, 64, Encoding::Srgb, 3);
  double previous = 0.0;
  for (float amount : {0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
    const double mean = meanOf(ldrFlip(base, perturbed(base, amount)));
    EXPECT_GT(mean, previous) << "amount " << amount;
    previous = mean;
  }
}

TEST(Flip, IsSymmetric) {
  const Image a = texture(40, 40, Encoding::Srgb, 4);
  const Image b = perturbed(a, 0.15f);
  const FlipMap ab = ldrFlip(a, b), ba = ldrFlip(b, a);
  for (std::size_t i = 0; i < ab.error.size(); ++i) ASSERT_NEAR(ab.error[i], ba.error[i], 1e-5f);
}

TEST(Flip, BlackAgainstWhiteIsAlmostMaximal) {
  Image black = makeImage(32, 32, Encoding::Srgb), white = makeImage(32, 32, Encoding::Srgb);
  std::fill(white.rgba.begin(), white.rgba.end(), 1.0f);
  const double mean = meanOf(ldrFlip(black, white));
  EXPECT_GT(mean, 0.8);
  EXPECT_LE(mean, 1.0);
}

TEST(Flip, ErrorIsLocalToTheChange) {
  const Image a = texture(128, 128, Encoding::Srgb, 5);
  Image b = a;
  float* p = &b.rgba[(64 * 128 + 64) * 4];
  p[0] = p[1] = p[2] = 1.0f;  // one bright pixel
  const FlipMap m = ldrFlip(a, b);
  EXPECT_GT(m.error[64 * 128 + 64], 0.05f);
  EXPECT_EQ(m.error[5 * 128 + 5], 0.0f);  // far corner: beyond every filter's reach
}

TEST(Flip, DefaultObserverIsAbout67PixelsPerDegree) { EXPECT_NEAR(defaultPixelsPerDegree(), 67.02, 0.01); }

TEST(HdrFlip, AcesMapsTheStartExposureOfTheBrightestPixelTo085) {
  Image hdr = makeImage(4, 4, Encoding::Linear);
  for (std::size_t i = 0; i < hdr.rgba.size(); ++i) hdr.rgba[i] = 1.0f;  // luminance 1 everywhere
  hdr.rgba[0] = hdr.rgba[1] = hdr.rgba[2] = 16.0f;                        // one pixel at 16
  const ExposureRange r = hdrExposureRange(hdr);
  EXPECT_NEAR(acesToneMap(16.0f, r.start), 0.85f, 1e-4f);
  EXPECT_NEAR(acesToneMap(1.0f, r.stop), 0.85f, 1e-4f);  // the median luminance is 1
  EXPECT_NEAR(r.stop - r.start, 4.0, 1e-9);               // log2(16 / 1)
  EXPECT_EQ(r.count, 4);
}

// The exposure range's median and maximum luminance come from a radix selection: check them
// against std::nth_element on an image with ties, black, negative and non-finite pixels.
TEST(HdrFlip, ExposureRangeUsesTheExactMedianLuminance) {
  for (const bool mostlyBlack : {false, true}) {
    Image hdr = makeImage(123, 77, Encoding::Linear);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> value(0.0f, 30.0f);
    for (std::size_t i = 0; i < hdr.pixelCount(); ++i) {
      float* p = &hdr.rgba[i * 4];
      const bool black = mostlyBlack ? i % 4 != 0 : i % 7 == 0;
      for (int c = 0; c < 3; ++c) p[c] = black ? 0.0f : (i % 11 == 0 ? 2.0f : value(rng));
      if (i % 13 == 0) p[1] = -1.0f;
      if (i == 5) p[0] = std::numeric_limits<float>::quiet_NaN();
      if (i == 6) p[2] = std::numeric_limits<float>::infinity();
    }
    std::vector<float> lum;
    for (std::size_t i = 0; i < hdr.pixelCount(); ++i) {
      const float* p = &hdr.rgba[i * 4];
      const float y = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
      lum.push_back(std::isfinite(y) ? std::max(0.0f, y) : 0.0f);
    }
    float yMax = 0.0f;
    for (float v : lum) yMax = std::max(yMax, v);
    std::vector<float> sorted = lum;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    float yMedian = sorted[sorted.size() / 2];
    if (yMedian <= 0.0f) {
      yMedian = yMax;
      for (float v : lum) if (v > 0.0f) yMedian = std::min(yMedian, v);
    }
    const ExposureRange r = hdrExposureRange(hdr);
    // acesToneMap(y, exposure) = 0.85 exactly where exposure = log2(x / y): the same x for both.
    EXPECT_NEAR(r.stop - r.start, std::log2(static_cast<double>(yMax) / static_cast<double>(yMedian)), 1e-10) << mostlyBlack;
    EXPECT_NEAR(acesToneMap(yMax, r.start), 0.85f, 1e-4f);
  }
}

TEST(HdrFlip, IdenticalIsZeroAndDifferencesAreBounded) {
  Image a = texture(48, 32, Encoding::Linear, 6);
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) a.rgba[i] *= 8.0f;  // HDR range
  const HdrFlipResult same = hdrFlip(a, a);
  EXPECT_EQ(*std::max_element(same.map.error.begin(), same.map.error.end()), 0.0f);
  EXPECT_GE(same.exposures, 2);
  Image b = a;
  for (std::size_t i = 0; i < b.rgba.size(); i += 4) b.rgba[i + 1] *= 1.5f;
  const HdrFlipResult diff = hdrFlip(a, b);
  const auto [lo, hi] = std::minmax_element(diff.map.error.begin(), diff.map.error.end());
  EXPECT_GE(*lo, 0.0f);
  EXPECT_LE(*hi, 1.0f);
  EXPECT_GT(meanOf(diff.map), 0.01);
}

TEST(HdrFlip, CompareImagesUsesHdrFlipForLinearPairs) {
  const Image a = texture(32, 32, Encoding::Linear, 7);
  const ImageMetrics m = compareImages(a, perturbed(a, 0.3f)).metrics;
  ASSERT_TRUE(m.flip);
  EXPECT_EQ(m.flip->mode, "hdr");
  EXPECT_GT(m.flip->mean, 0.0);
}

}  // namespace
}  // namespace fgb::harness
