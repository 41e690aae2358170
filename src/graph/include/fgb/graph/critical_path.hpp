// How much each pass holds the frame up: the critical path of a compiled schedule, weighted by
// each pass's cost (the pass-timing calibration's isolated costs). Pure: no Vulkan, no clocks.
#pragma once

#include <cstdint>
#include <fgb/graph/compiled_graph.hpp>
#include <span>
#include <vector>

namespace fgb::graph {

// Per declared node: the alive nodes that must end before it starts in `compiled`'s schedule:
// its dependency edges, the step before it on its queue, and the last step of every submit its
// own submit waits for (a timeline value on another queue). Culled nodes have none and are none's.
std::vector<std::vector<uint32_t>> schedulePredecessors(const CompiledGraph& compiled);

struct CriticalPath {
  double lengthMs = 0.0;            // the longest chain of costs through the schedule
  std::vector<double> shareOfPath;  // per node: how much shorter the path is without its cost, / lengthMs
  std::vector<bool> onPath;         // per node: on one longest chain
};

// Longest path through `predecessors` (a DAG, as schedulePredecessors gives) with node weights
// `costMs` (same indexing; culled nodes cost 0). A pass's share is (L - L with its cost 0) / L:
// 0 for a pass off every critical chain, its cost / L for one that no other chain could replace.
CriticalPath criticalPath(const std::vector<std::vector<uint32_t>>& predecessors, std::span<const double> costMs);

}  // namespace fgb::graph
