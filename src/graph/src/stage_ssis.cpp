// Stage: pruning redundant cross-queue edges (thesis Algorithm 3, after P. Muratov, "Organizing GPU
// Work with Directed Acyclic Graphs", 2020).
//
// σ(u) = order position + queue(u)·V + 1 numbers each queue's nodes contiguously (V alive nodes).
// For every node u and queue q ≠ queue(u), SSIS_q(u) is the largest σ of a dependency of u on queue q: waiting for
// a point on q at or after it is sufficient. `known[u]` is what u is already ordered after: its own
// σ on its queue, everything the previous node on its queue knew (a wait blocks the rest of the
// queue), and everything known by the dependencies it waits for. The greedy loop adds, while some
// queue is not yet covered, the dependency that covers the most queues (ties: larger σ) — that
// edge joins G*. Using the dependency's `known` (not only its own σ) makes the cover transitive.
#include <algorithm>

#include "compile_state.hpp"

namespace fgb::graph::detail {
namespace {

// How many of the queues on which `have` is short of `required` `candidate` covers.
uint32_t newlyCovered(const QueueArray& required, const QueueArray& have, const QueueArray& candidate,
                      uint32_t queues) {
  uint32_t count = 0;
  for (uint32_t q = 0; q < queues; ++q) count += have[q] < required[q] && candidate[q] >= required[q] ? 1 : 0;
  return count;
}

bool covers(const QueueArray& have, const QueueArray& required, uint32_t queues) {
  for (uint32_t q = 0; q < queues; ++q) {
    if (have[q] < required[q]) return false;
  }
  return true;
}

}  // namespace

void pruneCrossQueueEdges(CompileState& state) {
  // One queue has no cross-queue edges: nothing to prune, and nobody asks what σ a node knows.
  const uint32_t queues = state.queueCount;
  if (queues == 1) return;
  const auto& order = state.out.order;
  const auto aliveCount = static_cast<uint32_t>(order.size());
  state.sigma.assign(state.nodeCount, 0);
  state.known.assign(state.nodeCount, QueueArray{});
  for (uint32_t position = 0; position < aliveCount; ++position) {
    const uint32_t u = order[position];
    state.sigma[u] = position + state.queueOf[u] * aliveCount + 1;
  }
  // What the last node so far on each queue knew (a wait blocks the rest of its queue).
  std::array<QueueArray, kQueueClassCount> knownOnQueue{};
  for (const uint32_t u : order) {
    const uint32_t queue = state.queueOf[u];
    QueueArray have = knownOnQueue[queue];
    have[queue] = state.sigma[u];
    // SSIS_q(u) for every queue q. On u's own queue it is below σ(u), so never uncovered.
    QueueArray required{};
    for (uint32_t e = state.edgeStart[u]; e < state.edgeEnd[u]; ++e) {
      const uint32_t v = state.out.edges[e].from;
      required[state.queueOf[v]] = std::max(required[state.queueOf[v]], state.sigma[v]);
    }
    // Greedy cover: the dependency covering the most uncovered queues, ties to the larger σ. The
    // dependency with the largest σ on an uncovered queue covers it, so each round covers one.
    while (!covers(have, required, queues)) {
      uint32_t best = kInvalidIndex;
      uint32_t bestCover = 0;
      for (uint32_t e = state.edgeStart[u]; e < state.edgeEnd[u]; ++e) {
        const uint32_t v = state.out.edges[e].from;
        const uint32_t cover = newlyCovered(required, have, state.known[v], queues);
        if (best == kInvalidIndex || cover > bestCover || (cover == bestCover && state.sigma[v] > state.sigma[best])) {
          best = v;
          bestCover = cover;
        }
      }
      state.out.syncEdges.push_back({best, u});
      for (uint32_t q = 0; q < queues; ++q) have[q] = std::max(have[q], state.known[best][q]);
    }
    state.known[u] = have;
    knownOnQueue[queue] = have;
  }
}

}  // namespace fgb::graph::detail
