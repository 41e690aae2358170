#include <fgb/harness/stats/mann_whitney.hpp>
#include <fgb/harness/stats/pareto.hpp>

namespace fgb::harness {

Order compareTime(std::span<const double> a, std::span<const double> b, double alpha) {
  const MannWhitneyResult test = mannWhitneyU(a, b);
  if (test.pALess < alpha) return Order::Better;
  if (test.pAGreater < alpha) return Order::Worse;
  return Order::Equal;
}

Order compareError(double a, double b, double floor) {
  if (a < b - floor) return Order::Better;
  if (a > b + floor) return Order::Worse;
  return Order::Equal;
}

bool dominates(const TradeoffPoint& a, const TradeoffPoint& b, const DominanceOptions& options) {
  const Order time = compareTime(a.timeSamples, b.timeSamples, options.alpha);
  const Order error = compareError(a.error, b.error, options.errorFloor);
  if (time == Order::Worse || error == Order::Worse) return false;
  return time == Order::Better || error == Order::Better;
}

FrontAnalysis paretoFront(std::span<const TradeoffPoint> points, const DominanceOptions& options) {
  FrontAnalysis analysis;
  analysis.onFront.assign(points.size(), true);
  analysis.dominatedBy.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (i != j && dominates(points[j], points[i], options)) {
        analysis.dominatedBy[i].push_back(j);
        analysis.onFront[i] = false;
      }
    }
  }
  return analysis;
}

}  // namespace fgb::harness
