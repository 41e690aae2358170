#include <fgb/harness/stats.hpp>

#include <algorithm>
#include <cmath>
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
  summary.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / static_cast<double>(sorted.size());
  return summary;
}

bool isUnstable(const Summary& summary, double spreadLimit) {
  if (summary.n < 2 || summary.median <= 0.0) return false;
  return (summary.p95 - summary.p5) / summary.median > spreadLimit;
}

}  // namespace fgb::harness
