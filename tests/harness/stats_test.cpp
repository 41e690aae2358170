#include <fgb/harness/stats/stats.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace fgb::harness {
namespace {

TEST(Stats, SummaryOfKnownSamples) {
  const std::vector<double> samples{5, 1, 4, 2, 3};
  const Summary s = summarize(samples);
  EXPECT_EQ(s.n, 5u);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  EXPECT_DOUBLE_EQ(s.p5, 1.2);   // position 0.05 * 4 = 0.2 between 1 and 2
  EXPECT_DOUBLE_EQ(s.p95, 4.8);  // position 3.8 between 4 and 5
}

TEST(Stats, EvenCountMedianInterpolates) {
  const std::vector<double> samples{1, 2, 3, 10};
  EXPECT_DOUBLE_EQ(summarize(samples).median, 2.5);
}

TEST(Stats, EmptyInputIsAllZero) {
  const Summary s = summarize(std::vector<double>{});
  EXPECT_EQ(s.n, 0u);
  EXPECT_EQ(s.median, 0.0);
}

TEST(Stats, OutlierMakesPassUnstable) {
  EXPECT_TRUE(isUnstable(summarize(std::vector<double>{1, 1, 1, 1, 10})));
  EXPECT_FALSE(isUnstable(summarize(std::vector<double>{10, 10.1, 9.9, 10, 10})));
  EXPECT_FALSE(isUnstable(summarize(std::vector<double>{0, 0, 0})));  // zero median: never flagged
}

std::vector<double> oneTo(std::size_t n) {
  std::vector<double> v;
  for (std::size_t i = 1; i <= n; ++i) v.push_back(static_cast<double>(i));
  return v;
}

TEST(MedianInterval, BinomialTailIsExact) {
  EXPECT_NEAR(binomialHalfCdf(10, 2), 56.0 / 1024.0, 1e-12);  // (1 + 10 + 45) / 2^10
  EXPECT_DOUBLE_EQ(binomialHalfCdf(10, 10), 1.0);
  EXPECT_NEAR(binomialHalfCdf(2000, 999), 0.5 - 0.5 * 0.017839, 1e-4);  // 1/2 - P(B = 1000) / 2
}

TEST(MedianInterval, TenSamplesUseRanksTwoAndNine) {
  // 1 - 2 P(B <= 1) = 0.9785 >= 95%, while ranks 3 and 8 cover only 1 - 2 P(B <= 2) = 0.89.
  std::vector<double> samples = oneTo(10);
  std::swap(samples[0], samples[7]);  // any order
  const MedianInterval ci = medianConfidenceInterval(samples);
  EXPECT_EQ(ci.lowerRank, 2u);
  EXPECT_EQ(ci.upperRank, 9u);
  EXPECT_DOUBLE_EQ(ci.lower, 2.0);
  EXPECT_DOUBLE_EQ(ci.upper, 9.0);
  EXPECT_DOUBLE_EQ(ci.median, 5.5);
  EXPECT_NEAR(ci.coverage, 1.0 - 2.0 * 11.0 / 1024.0, 1e-12);
}

TEST(MedianInterval, HundredSamplesMatchTheTable) {
  // Standard tables give ranks 40 and 61 for n = 100 at 95% (coverage 0.9648).
  const MedianInterval ci = medianConfidenceInterval(oneTo(100));
  EXPECT_EQ(ci.lowerRank, 40u);
  EXPECT_EQ(ci.upperRank, 61u);
  EXPECT_NEAR(ci.coverage, 0.9648, 1e-3);
  EXPECT_NEAR(ci.relativeHalfWidth(), (61.0 - 40.0) / (2.0 * 50.5), 1e-12);
}

TEST(MedianInterval, TooFewSamplesGiveTheRangeAndSaySo) {
  const MedianInterval ci = medianConfidenceInterval(oneTo(5));
  EXPECT_DOUBLE_EQ(ci.lower, 1.0);
  EXPECT_DOUBLE_EQ(ci.upper, 5.0);
  EXPECT_NEAR(ci.coverage, 1.0 - 2.0 / 32.0, 1e-12);  // 93.75% < 95%
  EXPECT_TRUE(std::isinf(ci.relativeHalfWidth()));
  EXPECT_EQ(medianConfidenceInterval(std::vector<double>{}).n, 0u);
}

TEST(MedianInterval, NarrowsAsSamplesGrow) {
  // The same spread of values, more of them: the interval's half-width shrinks about as 1/sqrt(n).
  auto spread = [](std::size_t n) {
    std::vector<double> v;
    // 10 + a permutation of 0, 10/n, 20/n, ...: uniform over [10, 20) in a scrambled order.
    for (std::size_t i = 0; i < n; ++i) v.push_back(10.0 + 10.0 * static_cast<double>(i * 7919 % n) / static_cast<double>(n));
    return medianConfidenceInterval(v).relativeHalfWidth();
  };
  EXPECT_GT(spread(20), spread(200));
  EXPECT_GT(spread(200), spread(2000));
  EXPECT_LT(spread(2000), 0.02);
}

}  // namespace
}  // namespace fgb::harness
