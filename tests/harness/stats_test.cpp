#include <fgb/harness/stats.hpp>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace fgb::harness
