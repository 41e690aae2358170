// Stage: the execution order. The level of a node (computed with its dependencies) is the length
// of the longest path from a source (not the shortest, as the thesis text says): only then does
// every edge go from a lower to a strictly higher level, so sorting by level keeps the order
// topological.
#include "compile_state.hpp"

namespace fgb::graph::detail {

void sortByLevel(CompileState& state) {
  // Counting sort by level; within a level, declaration order (deterministic, and stable).
  std::vector<uint32_t> levelStart(size_t{state.maxLevel} + 2, 0);
  for (uint32_t n = 0; n < state.nodeCount; ++n) {
    if (state.alive[n]) ++levelStart[state.out.nodes[n].level + 1];
  }
  for (size_t l = 1; l < levelStart.size(); ++l) levelStart[l] += levelStart[l - 1];
  auto& order = state.out.order;
  order.resize(levelStart.back());
  for (uint32_t n = 0; n < state.nodeCount; ++n) {
    if (!state.alive[n]) continue;  // culled nodes keep level 0 and no order position
    const uint32_t position = levelStart[state.out.nodes[n].level]++;
    order[position] = n;
    state.out.nodes[n].orderIndex = position;
  }
}

}  // namespace fgb::graph::detail
