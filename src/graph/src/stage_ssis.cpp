// Stage: pruning redundant cross-queue edges (thesis Algorithm 3, after P. Muratov, "Organizing GPU
// Work with Directed Acyclic Graphs", 2020).
//
// σ(u) = order position + queue(u)·V + 1 numbers each queue's nodes contiguously. For every node u
// and queue q ≠ queue(u), SSIS_q(u) is the largest σ of a dependency of u on queue q: waiting for
// a point on q at or after it is sufficient. `known[u]` is what u is already ordered after: its own
// σ on its queue, everything the previous node on its queue knew (a wait blocks the rest of the
// queue), and everything known by the dependencies it waits for. The greedy loop adds, while some
// queue is not yet covered, the dependency that covers the most queues (ties: larger σ) — that
// edge joins G*. Using the dependency's `known` (not only its own σ) makes the cover transitive.
#include "compile_state.hpp"

namespace fgb::graph::detail {
namespace {

uint32_t countNewlyCovered(const QueueArray& required, const QueueArray& have, const QueueArray& candidate,
                           uint32_t queues) {
  uint32_t covered = 0;
  for (uint32_t q = 0; q < queues; ++q) {
    if (have[q] < required[q] && candidate[q] >= required[q]) ++covered;
  }
  return covered;
}

bool allCovered(const QueueArray& required, const QueueArray& have, uint32_t queues) {
  for (uint32_t q = 0; q < queues; ++q) {
    if (have[q] < required[q]) return false;
  }
  return true;
}

}  // namespace

void pruneCrossQueueEdges(CompileState& state) {
  const auto& order = state.out.order;
  const uint32_t queues = state.options.queueCount;
  const auto orderSize = static_cast<uint32_t>(order.size());
  state.sigma.assign(state.nodeCount, 0);
  state.known.assign(state.nodeCount, QueueArray{0, 0, 0});
  for (uint32_t position = 0; position < orderSize; ++position) {
    const uint32_t node = order[position];
    state.sigma[node] = position + state.queueOf[node] * orderSize + 1;
  }

  ScratchVector<uint32_t> previousOnQueue(queues, kInvalidIndex);
  for (const uint32_t u : order) {
    const uint32_t queue = state.queueOf[u];
    QueueArray have{0, 0, 0};
    if (previousOnQueue[queue] != kInvalidIndex) have = state.known[previousOnQueue[queue]];
    have[queue] = state.sigma[u];
    previousOnQueue[queue] = u;

    QueueArray required{0, 0, 0};
    const Adjacency& preds = state.predecessors;
    for (uint32_t i = preds.begin(u); i < preds.end(u); ++i) {
      const uint32_t v = preds.items[i];
      const uint32_t q = state.queueOf[v];
      if (q != queue && state.sigma[v] > required[q]) required[q] = state.sigma[v];
    }

    while (!allCovered(required, have, queues)) {
      uint32_t best = kInvalidIndex;
      uint32_t bestCover = 0;
      for (uint32_t i = preds.begin(u); i < preds.end(u); ++i) {
        const uint32_t v = preds.items[i];
        if (state.queueOf[v] == queue) continue;
        const uint32_t cover = countNewlyCovered(required, have, state.known[v], queues);
        if (cover > bestCover || (cover == bestCover && cover > 0 && state.sigma[v] > state.sigma[best])) {
          best = v;
          bestCover = cover;
        }
      }
      // The dependency with the largest σ on an uncovered queue always covers it, so best exists.
      state.out.syncEdges.push_back({best, u});
      for (uint32_t q = 0; q < queues; ++q) {
        if (state.known[best][q] > have[q]) have[q] = state.known[best][q];
      }
    }
    state.known[u] = have;
  }
}

}  // namespace fgb::graph::detail
