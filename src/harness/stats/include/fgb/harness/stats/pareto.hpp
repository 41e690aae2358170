// Time against error: which configurations are worth picking. A configuration is dominated when
// another one is
//   - significantly faster (one-sided Mann–Whitney on the frame-time samples, p < alpha) or equal
//     in time (neither is significantly faster than the other), and
//   - lower or equal in error beyond the reference's noise floor (error <= other's + floor),
// and strictly better in one of the two (significantly faster, or lower in error by more than the
// floor). The Pareto front is the configurations no other one dominates. Because "equal" means
// "not significantly different", dominance is not transitive; the front is still well defined.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace fgb::harness {

struct TradeoffPoint {
  std::span<const double> timeSamples;  // per-frame times (ms); at least one, all finite
  double error = 0.0;                   // error against the reference (lower is better)
};

struct DominanceOptions {
  double alpha = 0.05;      // significance level of the time comparison
  double errorFloor = 0.0;  // the reference's noise floor: smaller error differences are ties
};

enum class Order { Better, Equal, Worse };

// Time of `a` against `b`: Better when a is significantly faster.
Order compareTime(std::span<const double> a, std::span<const double> b, double alpha);
// Error of `a` against `b`: Better when lower by more than the floor, Worse when higher by more.
Order compareError(double a, double b, double floor);

bool dominates(const TradeoffPoint& a, const TradeoffPoint& b, const DominanceOptions& options);

struct FrontAnalysis {
  std::vector<bool> onFront;                          // per point
  std::vector<std::vector<std::size_t>> dominatedBy;  // per point: the points that dominate it
};

FrontAnalysis paretoFront(std::span<const TradeoffPoint> points, const DominanceOptions& options);

}  // namespace fgb::harness
