#include <fgb/harness/stats/mann_whitney.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace fgb::harness {
namespace {

TEST(MannWhitney, CompleteSeparationExact) {
  // U = 9 for a = {4,5,6} over b = {1,2,3}: only 1 of the C(6,3) = 20 arrangements is that extreme.
  const std::vector<double> a{4, 5, 6}, b{1, 2, 3};
  const auto r = mannWhitneyU(a, b);
  EXPECT_TRUE(r.exact);
  EXPECT_DOUBLE_EQ(r.uA, 9.0);
  EXPECT_DOUBLE_EQ(r.uB, 0.0);
  EXPECT_NEAR(r.pAGreater, 1.0 / 20.0, 1e-12);
  EXPECT_NEAR(r.pALess, 1.0, 1e-12);
  EXPECT_NEAR(r.pTwoSided, 0.1, 1e-12);
}

TEST(MannWhitney, InterleavedExactMatchesHandCount) {
  // a = {1,3,5}, b = {2,4,6}: ranks of a 1+3+5 = 9, U = 9 - 6 = 3. The null distribution of U for
  // 3 vs 3 has counts 1,1,2,3,3,3,3,2,1,1 for U = 0..9: P(U <= 3) = 7/20, P(U >= 3) = 16/20.
  const std::vector<double> a{1, 3, 5}, b{2, 4, 6};
  const auto r = mannWhitneyU(a, b);
  EXPECT_DOUBLE_EQ(r.uA, 3.0);
  EXPECT_NEAR(r.pALess, 7.0 / 20.0, 1e-12);
  EXPECT_NEAR(r.pAGreater, 16.0 / 20.0, 1e-12);
}

TEST(MannWhitney, TiesUseMidRanksAndTieCorrectedNormal) {
  // Ranks: 1(a) 3(a) 3(a) 3(b) 5(b) 6(b) -> R_a = 7, U_a = 1. Tie group of 3: sum(t^3 - t) = 24.
  // sigma^2 = 3*3/12 * (7 - 24/30) = 4.65; p_less = Phi((1 + 0.5 - 4.5) / sqrt(4.65)).
  const std::vector<double> a{1, 2, 2}, b{2, 3, 4};
  const auto r = mannWhitneyU(a, b);
  EXPECT_FALSE(r.exact);
  EXPECT_DOUBLE_EQ(r.uA, 1.0);
  EXPECT_NEAR(r.pALess, 0.0820798642, 1e-9);
  EXPECT_NEAR(r.pAGreater, 0.9681987152, 1e-9);
}

TEST(MannWhitney, AllEqualGivesNoEvidence) {
  const std::vector<double> a(10, 1.0), b(12, 1.0);
  const auto r = mannWhitneyU(a, b);
  EXPECT_DOUBLE_EQ(r.pAGreater, 1.0);
  EXPECT_DOUBLE_EQ(r.pALess, 1.0);
}

TEST(MannWhitney, LargeShiftedSamplesAreSignificant) {
  std::vector<double> a, b;
  for (int i = 0; i < 64; ++i) {
    b.push_back(1.0 + 0.01 * std::sin(i * 1.7));
    a.push_back(1.1 + 0.01 * std::sin(i * 2.3));
  }
  const auto r = mannWhitneyU(a, b);
  EXPECT_FALSE(r.exact);
  EXPECT_LT(r.pAGreater, 1e-10);
  EXPECT_GT(r.pALess, 0.99);
}

TEST(MannWhitney, ExactAndNormalAgreeRoughlyAtTheLimit) {
  std::vector<double> a, b;
  for (int i = 0; i < 30; ++i) {
    a.push_back(i * 2.0 + 1.3);  // no ties with b
    b.push_back(i * 2.0);
  }
  const auto exact = mannWhitneyU(a, b);
  ASSERT_TRUE(exact.exact);
  a.push_back(1000.0);  // 31 > limit: normal approximation
  const auto normal = mannWhitneyU(a, b);
  ASSERT_FALSE(normal.exact);
  EXPECT_NEAR(exact.pAGreater, 0.43, 0.1);
  EXPECT_NEAR(normal.pAGreater, exact.pAGreater, 0.1);
}

TEST(MannWhitney, RejectsEmptyAndNonFinite) {
  const std::vector<double> empty, one{1.0}, nan{std::nan("")};
  EXPECT_THROW(mannWhitneyU(empty, one), std::invalid_argument);
  EXPECT_THROW(mannWhitneyU(one, nan), std::invalid_argument);
}

}  // namespace
}  // namespace fgb::harness
