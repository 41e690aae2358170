// Mann–Whitney U (Wilcoxon rank-sum) test: do samples of `a` tend to be larger than those of `b`?
// Exact null distribution for small samples without ties; otherwise the normal approximation with
// tie correction and continuity correction.
#pragma once

#include <cstddef>
#include <span>

namespace fgb::harness {

struct MannWhitneyResult {
  double uA = 0.0;         // pairs (a_i, b_j) with a_i > b_j, ties counted as 1/2
  double uB = 0.0;         // n_a * n_b - uA
  double z = 0.0;          // standardised uA (normal approximation; 0 when exact)
  double pAGreater = 1.0;  // one-sided p-value for "a tends to be larger than b"
  double pALess = 1.0;     // one-sided p-value for "a tends to be smaller than b"
  double pTwoSided = 1.0;
  bool exact = false;      // true when the exact distribution was used
};

// Largest sample size per group for the exact distribution (beyond it the normal approximation is
// accurate to well under the significance levels we use).
inline constexpr std::size_t kMannWhitneyExactLimit = 30;

// Throws std::invalid_argument when a group is empty or holds a non-finite value.
MannWhitneyResult mannWhitneyU(std::span<const double> a, std::span<const double> b);

// Standard normal cumulative distribution function.
double normalCdf(double x);

}  // namespace fgb::harness
