// Stage: the execution order. The level of a node (computed with its dependencies) is the length
// of the longest path from a source (not the shortest, as the thesis text says): only then does
// every edge go from a lower to a strictly higher level, so sorting by level keeps the order
// topological.
#include "compile_state.hpp"

namespace fgb::graph::detail {

void sortByLevel(CompileState& state) {
  // Counting sort by level; within a level, declaration order (deterministic, and stable). Culled
  // nodes go to a bucket after the last level, which is then cut off: choosing the bucket (and
  // what a node's NodeInfo says) by a mask costs less than a branch on whether a node is alive,
  // which is as good as random.
  const uint32_t culledBucket = state.maxLevel + 1;
  auto aliveMask = [&](uint32_t n) { return 0u - uint32_t{state.alive[n]}; };  // all ones if alive
  auto bucketOf = [&](uint32_t n) { return state.level[n] ^ ((state.level[n] ^ culledBucket) & ~aliveMask(n)); };
  ScratchVector<uint32_t> bucketStart(size_t{culledBucket} + 2, 0);
  for (uint32_t n = 0; n < state.nodeCount; ++n) ++bucketStart[bucketOf(n) + 1];
  for (uint32_t b = 1; b < bucketStart.size(); ++b) bucketStart[b] += bucketStart[b - 1];
  const uint32_t aliveCount = bucketStart[culledBucket];
  auto& order = state.out.order;
  order.resize(state.nodeCount);
  // With several queues, σ too (see SyncPoint), while the position is at hand.
  const bool severalQueues = state.queueCount > 1;
  if (severalQueues) state.sync.resize(state.nodeCount);
  for (uint32_t n = 0; n < state.nodeCount; ++n) {
    const uint32_t position = bucketStart[bucketOf(n)]++;
    order[position] = n;
    if (severalQueues) state.sync[n].sigma = position + state.queueOf[n] * aliveCount + 1;
    // Culled nodes keep what cullNodes reset them to: level 0, no order position.
    NodeInfo& info = state.out.nodes[n];
    info.level = state.level[n] & aliveMask(n);
    info.orderIndex = position | ~aliveMask(n);
  }
  order.resize(aliveCount);
}

}  // namespace fgb::graph::detail
