// Stage: pruning redundant cross-queue edges (thesis Algorithm 3, after P. Muratov, "Organizing GPU
// Work with Directed Acyclic Graphs", 2020).
//
// σ(u) = order position + queue(u)·V + 1 numbers each queue's nodes contiguously (see SyncPoint). For every node u
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

// `value` if `condition`, else 0, computed with a mask: the compiler keeps it branchless, where it
// may turn a conditional expression back into a branch (and whether it holds is as good as random).
uint32_t valueIf(bool condition, uint32_t value) { return value & (0u - static_cast<uint32_t>(condition)); }

// The queue of a node with σ `sigma` (see SyncPoint): σ on queue q lies in [q·V + 1, q·V + V].
uint32_t queueOfSigma(uint32_t sigma, uint32_t nodes) {
  static_assert(kQueueClassCount == 3);
  return static_cast<uint32_t>(sigma > nodes) + static_cast<uint32_t>(sigma > 2 * nodes);
}

// SSIS_q(u) for every queue q: the largest σ of a dependency of u on q (0: none). On u's own queue
// it is below σ(u), which u already knows, so it never counts as uncovered: no need to leave the
// own queue out edge by edge.
// Kept in registers, not indexed by queue: a store and reload through a variable index per edge
// would chain every edge's update on the previous one's store.
QueueArray requiredOnEachQueue(const Edge* first, const Edge* last, const SyncPoint* sync, uint32_t nodes) {
  static_assert(kQueueClassCount == 3);
  uint32_t required0 = 0;
  uint32_t required1 = 0;
  uint32_t required2 = 0;
  for (const Edge* e = first; e != last; ++e) {
    const uint32_t sigma = sync[e->from].sigma;
    const uint32_t q = queueOfSigma(sigma, nodes);
    required0 = std::max(required0, valueIf(q == 0, sigma));
    required1 = std::max(required1, valueIf(q == 1, sigma));
    required2 = std::max(required2, valueIf(q == 2, sigma));
  }
  return {required0, required1, required2};
}

// The dependency covering the most `uncovered` queues, ties to the larger σ: the largest
// (cover, σ) pair, taken without branches. The dependency with the largest σ on an uncovered queue
// always covers it, so one with a cover wins over every one without (whatever their σ). A
// dependency on u's own queue covers nothing new (what it knew, the node before u on the queue
// knew too, and u starts from that), so it never wins.
uint32_t bestCover(const Edge* first, const Edge* last, const SyncPoint* sync, const QueueArray& required,
                   uint32_t uncovered) {
  uint64_t bestScore = 0;
  uint32_t best = kInvalidIndex;
  for (const Edge* e = first; e != last; ++e) {
    const uint32_t v = e->from;
    const SyncPoint& point = sync[v];
    const uint32_t cover = countNewlyCovered(required, point.known, uncovered);
    const uint64_t score = uint64_t{cover} << 32 | point.sigma;
    best = valueIf(score > bestScore, v ^ best) ^ best;
    bestScore = std::max(bestScore, score);
  }
  return best;
}

}  // namespace

void pruneCrossQueueEdges(CompileState& state) {
  // One queue has no cross-queue edges: nothing to prune, and nobody asks what σ a node knows.
  if (state.queueCount == 1) return;
  const Edge* edges = state.out.edges.data();
  const auto nodes = static_cast<uint32_t>(state.out.order.size());
  const uint32_t* queueOf = state.queueOf.data();
  SyncPoint* sync = state.sync.data();  // σ set by sortByLevel

  // What the last node so far on each queue knew (a wait blocks the rest of its queue).
  std::array<QueueArray, kQueueClassCount> knownOnQueue{};
  for (const uint32_t u : state.out.order) {
    const uint32_t queue = queueOf[u];
    QueueArray have = knownOnQueue[queue];
    have[queue] = sync[u].sigma;

    // u's dependencies are edges[edgeStart[u] .. edgeEnd[u]), each one's `from`.
    const Edge* const first = edges + state.edgeStart[u];
    const Edge* const last = edges + state.edgeEnd[u];
    const QueueArray required = requiredOnEachQueue(first, last, sync, nodes);
    for (uint32_t uncovered = uncoveredQueues(required, have); uncovered != 0;
         uncovered = uncoveredQueues(required, have)) {
      const uint32_t best = bestCover(first, last, sync, required, uncovered);
      state.out.syncEdges.push_back({best, u});
      for (uint32_t q = 0; q < kQueueClassCount; ++q) have[q] = std::max(have[q], sync[best].known[q]);
    }
    sync[u].known = have;
    knownOnQueue[queue] = have;
  }
}

}  // namespace fgb::graph::detail
