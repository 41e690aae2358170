// Descriptive statistics of timing samples, as timings.json reports them.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace fgb::harness {

struct Summary {
  double median = 0.0;
  double p5 = 0.0;
  double p95 = 0.0;
  double p99 = 0.0;
  double mean = 0.0;
  double min = 0.0;
  double max = 0.0;
  std::size_t n = 0;
};

// Percentile p in [0, 100] of already sorted samples, linear interpolation between closest ranks
// (the "type 7" definition used by NumPy and R). Empty input gives 0.
double percentileOfSorted(std::span<const double> sorted, double p);

// Summary of samples (any order). Empty input gives an all-zero summary with n = 0.
Summary summarize(std::span<const double> samples);

// Relative spread (p95 - p5) / median above which a pass is flagged unstable.
inline constexpr double kDefaultUnstableSpread = 0.5;

// A pass is unstable when its samples spread widely around the median: its median is then a weak
// basis for budgets and regressions. Passes with a zero median are never flagged.
bool isUnstable(const Summary& summary, double spreadLimit = kDefaultUnstableSpread);

// A distribution-free confidence interval of the median: the order statistics x(l) and x(u)
// (1-based ranks in the sorted samples, u = n + 1 - l) with the largest l whose coverage
// P(l <= B < u), B ~ Binomial(n, 1/2), is at least `confidence` (exact binomial tail, computed in
// log space, so it holds for any n and any continuous distribution). Below 6 samples no pair of
// ranks reaches 95%: the interval is then [min, max] and `coverage` says how much it does cover.
struct MedianInterval {
  double median = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  double coverage = 0.0;  // achieved coverage probability of [lower, upper]
  std::size_t lowerRank = 0, upperRank = 0;  // 1-based; 0 when there are no samples
  std::size_t n = 0;

  // (upper - lower) / (2 * median): the interval's half-width relative to the median; +inf when
  // the median is not positive or the requested confidence was not reached.
  double relativeHalfWidth(double confidence = 0.95) const;
};

MedianInterval medianConfidenceInterval(std::span<const double> samples, double confidence = 0.95);

// P(B <= k) for B ~ Binomial(n, 1/2).
double binomialHalfCdf(std::size_t n, std::size_t k);

}  // namespace fgb::harness
