#include <fgb/harness/metrics/metrics.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace fgb::harness {
namespace {

Image filled(uint32_t w, uint32_t h, float v, Encoding e) {
  Image image = makeImage(w, h, e);
  for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = (i % 4 == 3) ? 1.0f : v;
  return image;
}

MetricOptions noFlip() {
  MetricOptions o;
  o.flip = false;
  return o;
}

TEST(Metrics, HandComputedErrorsOnTwoByTwo) {
  // One red channel of one pixel off by 0.1: MSE = 0.01 / 12 channels, PSNR = 10 log10(1200).
  const Image a = filled(2, 2, 0.5f, Encoding::Srgb);
  Image b = a;
  b.rgba[4 * 3 + 0] = 0.6f;
  const ImageMetrics m = compareImages(a, b, noFlip()).metrics;
  EXPECT_EQ(m.domain, "srgb");
  EXPECT_NEAR(m.maxAbsError, 0.1, 1e-6);
  EXPECT_NEAR(m.rmse, std::sqrt(0.01 / 12.0), 1e-6);
  EXPECT_NEAR(m.psnr, 10.0 * std::log10(1200.0), 1e-3);
  EXPECT_DOUBLE_EQ(m.shareOverThreshold, 0.25);
  EXPECT_EQ(m.nonFiniteReference + m.nonFiniteTest, 0u);
}

TEST(Metrics, IdenticalImagesHaveInfinitePsnrAndZeroFlip) {
  const Image a = filled(8, 8, 0.3f, Encoding::Srgb);
  const ImageMetrics m = compareImages(a, a).metrics;
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnr));
  ASSERT_TRUE(m.flip);
  EXPECT_EQ(m.flip->mean, 0.0);
  EXPECT_EQ(m.flip->max, 0.0);
  EXPECT_TRUE(toJson(m)["psnr_db"].is_null());
}

TEST(Metrics, LinearPeakIsLargestReferenceValue) {
  const Image a = filled(2, 1, 4.0f, Encoding::Linear);
  Image b = a;
  b.rgba[0] = 3.0f;  // MSE = 1/6
  const ImageMetrics m = compareImages(a, b, noFlip()).metrics;
  EXPECT_EQ(m.domain, "linear");
  EXPECT_DOUBLE_EQ(m.peak, 4.0);
  EXPECT_NEAR(m.psnr, 10.0 * std::log10(16.0 * 6.0), 1e-9);
}

TEST(Metrics, NonFinitePixelsAreCountedAndExcluded) {
  const Image a = filled(4, 1, 0.5f, Encoding::Linear);
  Image b = a;
  b.rgba[0] = std::numeric_limits<float>::quiet_NaN();
  b.rgba[4 + 1] = std::numeric_limits<float>::infinity();
  const Comparison c = compareImages(a, b);
  EXPECT_EQ(c.metrics.nonFiniteTest, 2u);
  EXPECT_EQ(c.metrics.nonFiniteReference, 0u);
  EXPECT_TRUE(c.metrics.hasNonFinite());
  EXPECT_EQ(c.metrics.rmse, 0.0);  // the other pixels agree
  EXPECT_EQ(c.nonFiniteMask[0], 1);
  EXPECT_EQ(c.nonFiniteMask[2], 0);
  ASSERT_TRUE(c.metrics.flip);
  EXPECT_TRUE(std::isfinite(c.metrics.flip->mean));
}

TEST(Metrics, MixedEncodingsCompareInSrgb) {
  const Image linear = filled(2, 2, 0.5f, Encoding::Linear);
  const Image srgb = toEncoding(linear, Encoding::Srgb);
  const ImageMetrics m = compareImages(linear, srgb, noFlip()).metrics;
  EXPECT_EQ(m.domain, "srgb");
  EXPECT_NEAR(m.maxAbsError, 0.0, 1e-6);
}

TEST(Metrics, SizeMismatchThrows) {
  EXPECT_THROW(compareImages(filled(2, 2, 0, Encoding::Srgb), filled(2, 3, 0, Encoding::Srgb)), std::invalid_argument);
}

TEST(Metrics, FlipSummaryPercentilesAreExact) {
  std::vector<float> errors;
  for (int i = 0; i <= 100; ++i) errors.push_back(static_cast<float>(i) / 100.0f);
  const FlipStatistics s = summarizeFlip(errors, "ldr");
  EXPECT_NEAR(s.mean, 0.5, 1e-6);
  EXPECT_NEAR(s.p50, 0.5, 1e-6);
  EXPECT_NEAR(s.p95, 0.95, 1e-6);
  EXPECT_NEAR(s.p99, 0.99, 1e-6);
  EXPECT_NEAR(s.max, 1.0, 1e-6);
}

// The percentiles come from a radix selection: check them against a full sort on awkward data
// (many ties and zeros, values spread over many binades, sizes around the interpolation points).
TEST(Metrics, FlipSummaryMatchesSortedPercentiles) {
  std::mt19937 rng(7);
  for (std::size_t n : {1u, 2u, 3u, 101u, 1000u, 100003u}) {
    std::vector<float> errors(n);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    for (std::size_t i = 0; i < n; ++i) {
      const float u = uniform(rng);
      errors[i] = i % 3 == 0 ? 0.0f : (i % 5 == 0 ? 0.25f : u * u * u * u);  // ties, zeros, small values
      if (i % 17 == 0) errors[i] = -u;  // not FLIP errors, but the summary orders any values
      if (i % 19 == 0) errors[i] = -0.0f;
    }
    std::vector<double> sorted(errors.begin(), errors.end());
    std::sort(sorted.begin(), sorted.end());
    auto percentile = [&](double p) {
      const double position = p / 100.0 * static_cast<double>(n - 1);
      const auto lower = static_cast<std::size_t>(position);
      if (lower + 1 >= n) return sorted[lower];
      return sorted[lower] + (sorted[lower + 1] - sorted[lower]) * (position - static_cast<double>(lower));
    };
    double sum = 0.0;
    for (double v : sorted) sum += v;
    const FlipStatistics s = summarizeFlip(errors, "hdr");
    EXPECT_EQ(s.p50, percentile(50.0)) << n;
    EXPECT_EQ(s.p95, percentile(95.0)) << n;
    EXPECT_EQ(s.p99, percentile(99.0)) << n;
    EXPECT_EQ(s.max, sorted.back()) << n;
    EXPECT_NEAR(s.mean, sum / static_cast<double>(n), 1e-12) << n;
  }
}

TEST(Metrics, HeatMapMarksNonFiniteGreenAndScalesErrors) {
  const std::vector<float> errors{0.0f, 1.0f, 0.5f};
  const std::vector<uint8_t> mask{0, 0, 1};
  const Image h = heatMap(errors, mask, 3, 1);
  EXPECT_EQ(h.encoding, Encoding::Srgb);
  EXPECT_LT(h.rgba[0] + h.rgba[1] + h.rgba[2], 0.1f);   // low error: dark
  EXPECT_GT(h.rgba[4] + h.rgba[5] + h.rgba[6], 2.5f);   // high error: bright
  EXPECT_FLOAT_EQ(h.rgba[8 + 1], 1.0f);                  // NaN: green
  EXPECT_FLOAT_EQ(h.rgba[8 + 0], 0.0f);
}

}  // namespace
}  // namespace fgb::harness
