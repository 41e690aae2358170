// Stage: dependency levels and the execution order. The level of a node is the length of the
// longest path from a source (not the shortest, as the thesis text says): only then does every edge
// go from a lower to a strictly higher level, so sorting by level keeps the order topological.
#include "compile_state.hpp"

namespace fgb::graph::detail {

void sortByLevel(CompileState& state) {
  const uint32_t count = state.nodeCount;
  const Adjacency& preds = state.predecessors;
  std::vector<uint32_t> level(count, 0);

  // Successor lists, to run Kahn's algorithm forwards.
  Adjacency succs;
  succs.start.assign(count + 1, 0);
  for (uint32_t i = 0; i < preds.items.size(); ++i) ++succs.start[preds.items[i] + 1];
  for (uint32_t n = 1; n <= count; ++n) succs.start[n] += succs.start[n - 1];
  succs.items.resize(preds.items.size());
  {
    std::vector<uint32_t> cursor(succs.start.begin(), succs.start.end() - 1);
    for (uint32_t n = 0; n < count; ++n) {
      for (uint32_t i = preds.begin(n); i < preds.end(n); ++i) succs.items[cursor[preds.items[i]]++] = n;
    }
  }

  std::vector<uint32_t> pending(count);
  std::vector<uint32_t> ready;
  uint32_t maxLevel = 0;
  for (uint32_t n = 0; n < count; ++n) {
    pending[n] = preds.end(n) - preds.begin(n);
    if (state.alive[n] && pending[n] == 0) ready.push_back(n);
  }
  while (!ready.empty()) {
    const uint32_t n = ready.back();
    ready.pop_back();
    for (uint32_t i = succs.begin(n); i < succs.end(n); ++i) {
      const uint32_t next = succs.items[i];
      if (level[next] < level[n] + 1) level[next] = level[n] + 1;
      if (level[next] > maxLevel) maxLevel = level[next];
      if (--pending[next] == 0) ready.push_back(next);
    }
  }

  std::vector<uint32_t> left;
  for (uint32_t n = 0; n < count; ++n) {
    if (state.alive[n] && pending[n] != 0) left.push_back(n);
  }
  if (!left.empty()) reportCycle(state, preds, left);

  // Counting sort by level; within a level, declaration order (deterministic, and stable).
  std::vector<uint32_t> levelStart(maxLevel + 2, 0);
  uint32_t aliveCount = 0;
  for (uint32_t n = 0; n < count; ++n) {
    if (!state.alive[n]) continue;
    ++levelStart[level[n] + 1];
    ++aliveCount;
  }
  for (uint32_t l = 1; l < levelStart.size(); ++l) levelStart[l] += levelStart[l - 1];
  state.out.order.resize(aliveCount);
  for (uint32_t n = 0; n < count; ++n) {
    if (!state.alive[n]) continue;
    const uint32_t position = levelStart[level[n]]++;
    state.out.order[position] = n;
    state.out.nodes[n].level = level[n];
    state.out.nodes[n].orderIndex = position;
  }
}

}  // namespace fgb::graph::detail
