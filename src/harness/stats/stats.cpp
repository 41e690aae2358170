#include <fgb/harness/stats/stats.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fgb::harness {

double percentileOfSorted(std::span<const double> sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double clamped = std::clamp(p, 0.0, 100.0);
  const double position = clamped / 100.0 * static_cast<double>(sorted.size() - 1);
  const auto lower = static_cast<std::size_t>(std::floor(position));
  const std::size_t upper = std::min(lower + 1, sorted.size() - 1);
  const double fraction = position - static_cast<double>(lower);
  return sorted[lower] + (sorted[upper] - sorted[lower]) * fraction;
}

Summary summarize(std::span<const double> samples) {
  Summary summary;
  if (samples.empty()) return summary;
  std::vector<double> sorted(samples.begin(), samples.end());
  std::sort(sorted.begin(), sorted.end());
  summary.n = sorted.size();
  summary.min = sorted.front();
  summary.max = sorted.back();
  summary.median = percentileOfSorted(sorted, 50.0);
  summary.p5 = percentileOfSorted(sorted, 5.0);
  summary.p95 = percentileOfSorted(sorted, 95.0);
  summary.p99 = percentileOfSorted(sorted, 99.0);
  summary.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(sorted.size());
  return summary;
}

bool isUnstable(const Summary& summary, double spreadLimit) {
  if (summary.n < 2 || summary.median <= 0.0) return false;
  return (summary.p95 - summary.p5) / summary.median > spreadLimit;
}

namespace {
// C(n, i) / 2^n from lgamma, so that n in the thousands neither overflows nor underflows.
double binomialHalfPmf(std::size_t n, std::size_t i) {
  const double nd = static_cast<double>(n), id = static_cast<double>(i);
  return std::exp(std::lgamma(nd + 1.0) - std::lgamma(id + 1.0) - std::lgamma(nd - id + 1.0) + nd * std::log(0.5));
}
}  // namespace

double binomialHalfCdf(std::size_t n, std::size_t k) {
  if (k >= n) return 1.0;
  double sum = 0.0;
  for (std::size_t i = 0; i <= k; ++i) sum += binomialHalfPmf(n, i);
  return std::min(sum, 1.0);
}

MedianInterval medianConfidenceInterval(std::span<const double> samples, double confidence) {
  MedianInterval interval;
  interval.n = samples.size();
  if (samples.empty()) return interval;
  std::vector<double> sorted(samples.begin(), samples.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  interval.median = percentileOfSorted(sorted, 50.0);
  // Coverage of [x(l), x(n+1-l)] is 1 - 2 P(B <= l - 1); it falls as l grows, so take the largest
  // l that still covers `confidence`, searching up from l = 1 (the [min, max] interval).
  std::size_t best = 1;
  double tail = binomialHalfPmf(n, 0);  // P(B <= l - 1), accumulated as l grows
  double bestCoverage = 1.0 - 2.0 * tail;
  for (std::size_t l = 2; l <= (n + 1) / 2; ++l) {
    tail += binomialHalfPmf(n, l - 1);
    const double coverage = 1.0 - 2.0 * tail;
    if (coverage < confidence) break;
    best = l;
    bestCoverage = coverage;
  }
  interval.lowerRank = best;
  interval.upperRank = n + 1 - best;
  interval.lower = sorted[interval.lowerRank - 1];
  interval.upper = sorted[interval.upperRank - 1];
  interval.coverage = n == 1 ? 0.0 : bestCoverage;
  return interval;
}

double MedianInterval::relativeHalfWidth(double confidence) const {
  if (n == 0 || median <= 0.0 || coverage < confidence) return std::numeric_limits<double>::infinity();
  return (upper - lower) / (2.0 * median);
}

}  // namespace fgb::harness
