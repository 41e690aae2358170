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

}  // namespace fgb::harness
