// Stage: dependency levels and the execution order. The level of a node is the length of the
// longest path from a source (not the shortest, as the thesis text says): only then does every edge
// go from a lower to a strictly higher level, so sorting by level keeps the order topological.
#include "compile_state.hpp"

#include <algorithm>

namespace fgb::graph::detail {

namespace {

// Longest-path levels by a depth-first walk over predecessors, in declaration order. Declaration
// order is nearly topological (producers come before readers), so the walk rarely goes deep, and
// it needs no successor lists. Returns false on a cycle, leaving it to levelsByKahn to report.
bool levelsDepthFirst(const Adjacency& preds, uint32_t count, ScratchVector<uint32_t>& level, uint32_t& maxLevel) {
  enum : uint8_t { kNew, kOnStack, kDone };
  ScratchVector<uint8_t> mark(count, kNew);
  ScratchVector<uint32_t> stack;   // nodes being visited...
  ScratchVector<uint32_t> cursor;  // ...and the next predecessor each one looks at
  for (uint32_t root = 0; root < count; ++root) {
    if (mark[root] == kDone) continue;
    mark[root] = kOnStack;
    stack.push_back(root);
    cursor.push_back(preds.begin(root));
    while (!stack.empty()) {
      const uint32_t u = stack.back();
      uint32_t i = cursor.back();
      while (i < preds.end(u) && mark[preds.items[i]] == kDone) ++i;
      if (i < preds.end(u)) {  // a predecessor still to visit first
        const uint32_t p = preds.items[i];
        if (mark[p] == kOnStack) return false;
        cursor.back() = i;
        mark[p] = kOnStack;
        stack.push_back(p);
        cursor.push_back(preds.begin(p));
        continue;
      }
      uint32_t mine = 0;
      for (uint32_t k = preds.begin(u); k < preds.end(u); ++k) mine = std::max(mine, level[preds.items[k]] + 1);
      level[u] = mine;
      maxLevel = std::max(maxLevel, mine);
      mark[u] = kDone;
      stack.pop_back();
      cursor.pop_back();
    }
  }
  return true;
}

// Kahn's algorithm forwards over successor lists; reports a cycle if some alive node is left.
void levelsByKahn(const CompileState& state, ScratchVector<uint32_t>& level, uint32_t& maxLevel) {
  const uint32_t count = state.nodeCount;
  const Adjacency& preds = state.predecessors;
  level.assign(count, 0);
  maxLevel = 0;
  Adjacency succs;
  succs.start.assign(count + 1, 0);
  for (uint32_t i = 0; i < preds.items.size(); ++i) ++succs.start[preds.items[i] + 1];
  for (uint32_t n = 1; n <= count; ++n) succs.start[n] += succs.start[n - 1];
  succs.items.resize(preds.items.size());
  {
    ScratchVector<uint32_t> cursor(succs.start.begin(), succs.start.end() - 1);
    for (uint32_t n = 0; n < count; ++n) {
      for (uint32_t i = preds.begin(n); i < preds.end(n); ++i) succs.items[cursor[preds.items[i]]++] = n;
    }
  }

  ScratchVector<uint32_t> pending(count, 0);
  ScratchVector<uint32_t> ready;
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
}

}  // namespace

void sortByLevel(CompileState& state) {
  const uint32_t count = state.nodeCount;
  ScratchVector<uint32_t> level;
  level.resize(count);
  uint32_t maxLevel = 0;
  // Culled nodes have no edges, so both ways give them level 0; only alive levels are used.
  if (!levelsDepthFirst(state.predecessors, count, level, maxLevel)) levelsByKahn(state, level, maxLevel);

  // Counting sort by level; within a level, declaration order (deterministic, and stable).
  ScratchVector<uint32_t> levelStart(maxLevel + 2, 0);
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
