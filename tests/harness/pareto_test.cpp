#include <gtest/gtest.h>

#include <fgb/harness/stats/pareto.hpp>
#include <vector>

namespace fgb::harness {
namespace {

// n samples around `centre`: centre + (-0.5 .. 0.5) in a fixed scrambled order.
std::vector<double> timesAround(double centre, std::size_t n = 24) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i)
    v.push_back(centre - 0.5 + static_cast<double>(i * 7 % n) / static_cast<double>(n));
  return v;
}

TEST(Pareto, TimeOrderNeedsSignificance) {
  EXPECT_EQ(compareTime(timesAround(10), timesAround(12), 0.05), Order::Better);
  EXPECT_EQ(compareTime(timesAround(12), timesAround(10), 0.05), Order::Worse);
  // Overlapping samples: 10.0 vs 10.05 is no significant difference.
  EXPECT_EQ(compareTime(timesAround(10), timesAround(10.05), 0.05), Order::Equal);
  // Separated but only three samples each: the exact test cannot reach p < 0.05 one-sided (1/20).
  const std::vector<double> fast{1, 2, 3}, slow{4, 5, 6};
  EXPECT_EQ(compareTime(fast, slow, 0.05), Order::Equal);
  EXPECT_EQ(compareTime(fast, slow, 0.06), Order::Better);
}

TEST(Pareto, ErrorOrderIgnoresDifferencesWithinTheFloor) {
  EXPECT_EQ(compareError(0.10, 0.11, 0.0), Order::Better);
  EXPECT_EQ(compareError(0.10, 0.11, 0.02), Order::Equal);
  EXPECT_EQ(compareError(0.13, 0.10, 0.02), Order::Worse);
  EXPECT_EQ(compareError(0.10, 0.10, 0.0), Order::Equal);
}

TEST(Pareto, FasterAtEqualErrorDominates) {
  const auto fast = timesAround(10), slow = timesAround(12);
  const TradeoffPoint a{fast, 0.1}, b{slow, 0.1};
  EXPECT_TRUE(dominates(a, b, {}));
  EXPECT_FALSE(dominates(b, a, {}));
}

TEST(Pareto, LowerErrorAtEqualTimeDominates) {
  const auto t1 = timesAround(10), t2 = timesAround(10.05);
  const TradeoffPoint a{t1, 0.05}, b{t2, 0.1};
  EXPECT_TRUE(dominates(a, b, {}));
  EXPECT_FALSE(dominates(b, a, {}));
}

TEST(Pareto, TiesDominateNothing) {
  // The same samples and the same error: neither is strictly better, both stay on the front.
  const auto t = timesAround(10);
  const std::vector<TradeoffPoint> points{{t, 0.1}, {t, 0.1}};
  const FrontAnalysis front = paretoFront(points, {});
  EXPECT_TRUE(front.onFront[0]);
  EXPECT_TRUE(front.onFront[1]);
}

TEST(Pareto, NoiseFloorTurnsASmallErrorWinIntoATie) {
  // a is significantly faster; b's error is lower by 0.01.
  const auto fast = timesAround(10), slow = timesAround(12);
  const std::vector<TradeoffPoint> points{{fast, 0.11}, {slow, 0.10}};
  // Without a floor b's lower error is real: a trade-off, both on the front.
  const FrontAnalysis exact = paretoFront(points, {0.05, 0.0});
  EXPECT_TRUE(exact.onFront[0]);
  EXPECT_TRUE(exact.onFront[1]);
  // Within a floor of 0.02 the errors are equal and a, faster, dominates b.
  const FrontAnalysis noisy = paretoFront(points, {0.05, 0.02});
  EXPECT_TRUE(noisy.onFront[0]);
  EXPECT_FALSE(noisy.onFront[1]);
  EXPECT_EQ(noisy.dominatedBy[1], std::vector<std::size_t>{0});
}

TEST(Pareto, InsignificantSpeedUpDoesNotDominate) {
  // a looks faster on the medians but the samples overlap: equal time, equal error -> no dominance.
  const auto t1 = timesAround(10), t2 = timesAround(10.05);
  const std::vector<TradeoffPoint> points{{t1, 0.1}, {t2, 0.1}};
  const FrontAnalysis front = paretoFront(points, {});
  EXPECT_TRUE(front.onFront[0]);
  EXPECT_TRUE(front.onFront[1]);
}

TEST(Pareto, FrontOfAMixedSet) {
  // 0: fast, coarse. 1: slower, finer. 2: slower than 1 and coarser than 1 (dominated by 1).
  // 3: as fast as 0 and coarser (dominated by 0). 4: slowest, finest.
  const auto t10 = timesAround(10), t10b = timesAround(10.02), t14 = timesAround(14), t16 = timesAround(16),
             t20 = timesAround(20);
  const std::vector<TradeoffPoint> points{{t10, 0.30}, {t14, 0.10}, {t16, 0.20}, {t10b, 0.40}, {t20, 0.01}};
  const FrontAnalysis front = paretoFront(points, {0.05, 0.005});
  EXPECT_EQ(front.onFront, (std::vector<bool>{true, true, false, false, true}));
  EXPECT_EQ(front.dominatedBy[2], (std::vector<std::size_t>{1}));
  EXPECT_EQ(front.dominatedBy[3], (std::vector<std::size_t>{0}));
}

}  // namespace
}  // namespace fgb::harness
