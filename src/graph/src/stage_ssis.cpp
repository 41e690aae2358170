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

#include <algorithm>
#include <array>

namespace fgb::graph::detail {
namespace {

// Queues on which `have` is still short of `required`, as a bit mask (bit q: queue q). Queues past
// queueCount are never required, so they never count. Written without branches: which queues are
// short is as good as random, and a mispredicted branch costs more than the comparisons.
uint32_t uncoveredQueues(const QueueArray& required, const QueueArray& have) {
  static_assert(kQueueClassCount == 3);
  return static_cast<uint32_t>(have[0] < required[0]) | static_cast<uint32_t>(have[1] < required[1]) << 1 |
         static_cast<uint32_t>(have[2] < required[2]) << 2;
}

// How many of the `uncovered` queues `candidate` covers.
uint32_t countNewlyCovered(const QueueArray& required, const QueueArray& candidate, uint32_t uncovered) {
  const uint32_t covers = static_cast<uint32_t>(candidate[0] >= required[0]) |
                          static_cast<uint32_t>(candidate[1] >= required[1]) << 1 |
                          static_cast<uint32_t>(candidate[2] >= required[2]) << 2;
  const uint32_t newly = covers & uncovered;
  return (newly & 1u) + (newly >> 1 & 1u) + (newly >> 2);  // (no popcnt instruction in a generic build)
}

}  // namespace

void pruneCrossQueueEdges(CompileState& state) {
  // One queue has no cross-queue edges: nothing to prune, and nobody asks what σ a node knows.
  if (state.queueCount == 1) return;
  const auto& order = state.out.order;
  const Edge* edges = state.out.edges.data();
  const auto orderSize = static_cast<uint32_t>(order.size());
  state.sigma.assign(state.nodeCount, 0);
  state.known.assign(state.nodeCount, QueueArray{0, 0, 0});
  const uint32_t* queueOf = state.queueOf.data();
  uint32_t* sigma = state.sigma.data();
  QueueArray* known = state.known.data();
  // σ - 1 runs over [0, queueCount · V); nodeWithSigma inverts it.
  ScratchVector<uint32_t> nodeWithSigma(size_t{orderSize} * state.queueCount, kInvalidIndex);
  for (uint32_t position = 0; position < orderSize; ++position) {
    const uint32_t node = order[position];
    sigma[node] = position + queueOf[node] * orderSize + 1;
    nodeWithSigma[sigma[node] - 1] = node;
  }

  // What the last node so far on each queue knew (a wait blocks the rest of its queue).
  std::array<QueueArray, kQueueClassCount> knownOnQueue{};
  for (const uint32_t u : order) {
    const uint32_t queue = queueOf[u];
    QueueArray have = knownOnQueue[queue];
    have[queue] = sigma[u];

    // u's dependencies are edges[edgeStart[u] .. edgeEnd[u]), each one's `from`.
    const uint32_t first = state.edgeStart[u];
    const uint32_t last = state.edgeEnd[u];
    QueueArray required{0, 0, 0};
    for (uint32_t i = first; i < last; ++i) {
      const uint32_t v = edges[i].from;
      const uint32_t q = queueOf[v];
      required[q] = std::max(required[q], q != queue ? sigma[v] : 0u);
    }

    for (uint32_t uncovered = uncoveredQueues(required, have); uncovered != 0;
         uncovered = uncoveredQueues(required, have)) {
      // The dependency covering the most uncovered queues, ties to the larger σ: the largest
      // (cover, σ) pair, taken without branches (which one wins is as good as random).
      uint64_t best = 0;
      for (uint32_t i = first; i < last; ++i) {
        const uint32_t v = edges[i].from;
        const uint32_t cover = queueOf[v] == queue ? 0 : countNewlyCovered(required, known[v], uncovered);
        const uint64_t score = cover == 0 ? 0 : uint64_t{cover} << 32 | sigma[v];
        best = std::max(best, score);
      }
      // The dependency with the largest σ on an uncovered queue always covers it, so one wins;
      // σ names it (σ is unique per node).
      const uint32_t bestNode = nodeWithSigma[static_cast<uint32_t>(best) - 1];
      state.out.syncEdges.push_back({bestNode, u});
      for (uint32_t q = 0; q < kQueueClassCount; ++q) have[q] = std::max(have[q], known[bestNode][q]);
    }
    known[u] = have;
    knownOnQueue[queue] = have;
  }
}

}  // namespace fgb::graph::detail
