// Internal: transient memory aliasing by placement, driven by the walk over uses in execution
// order that also plans the barriers (see stage_barriers.cpp; the rules are in stage_aliasing.cpp).
// What the walk calls for every transient is defined here, inline: as calls into another file
// (saving and restoring registers each time) they cost about a twentieth of the walk.
#pragma once

#include "compile_state.hpp"
#include "requirements.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace fgb::graph::detail {

class TransientPlacer {
 public:
  // Starts an empty plan in state.out.aliasing; with `alias` false, nothing shares memory. With
  // `resolveRequirements`, each transient's memory requirements are resolved as it is placed (a
  // second walk over the same compile reuses them).
  TransientPlacer(CompileState& state, bool alias, bool resolveRequirements);

  // Places a transient at its first use, by `user` (the node being walked).
  void place(uint32_t resource, uint32_t user);
  // Hands its range back after its last user; later occupants wait for what the users did (on
  // each queue: the largest σ of a user, and the stages used).
  void release(uint32_t resource, const QueueArray& lastSigma, const std::array<StageMask, kQueueClassCount>& stages);
  // Sums the heap sizes into the plan's peak once every transient was placed and released.
  void finish();

 private:
  // A range of a heap nobody uses any more, with who used it last (per queue: the largest σ and
  // the stages).
  struct FreeRange {
    uint64_t offset;
    uint64_t size;
    QueueArray lastSigma;
    std::array<StageMask, kQueueClassCount> stages;
  };

  uint32_t heapFor(uint32_t resource, uint32_t memoryTypeBits);
  uint32_t findOrAddHeap(ResourceKind kind, uint32_t memoryTypeBits);
  [[nodiscard]] QueueArray reusableUpTo(uint32_t node) const;
  bool takeFreeRange(ScratchVector<FreeRange>& free, uint32_t user, const MemoryRequirements& req,
                     Placement& placement);

  CompileState& state_;
  AliasingPlan& plan_;
  bool alias_;
  bool resolveRequirements_;
  RequirementsResolver requirements_;
  uint32_t lastHeap_ = 0;                       // the heap the last transient went to
  std::vector<ScratchVector<FreeRange>> free_;  // per heap
};

// Device alignments are powers of two: a mask instead of a 64-bit division on the hot path.
inline uint64_t alignUp(uint64_t value, uint64_t alignment) {
  if ((alignment & (alignment - 1)) == 0) return (value + alignment - 1) & ~(alignment - 1);
  return (value + alignment - 1) / alignment * alignment;
}

inline uint32_t TransientPlacer::heapFor(uint32_t resource, uint32_t memoryTypeBits) {
  const ResourceKind kind = state_.kindOf(resource);
  // Neighbours in the walk usually share a heap: try the last one first.
  if (lastHeap_ < plan_.heaps.size() && plan_.heaps[lastHeap_].kind == kind &&
      plan_.heaps[lastHeap_].memoryTypeBits == memoryTypeBits) {
    return lastHeap_;
  }
  return findOrAddHeap(kind, memoryTypeBits);
}

// How far each queue is known to have run when `node` starts: a range whose last users on every
// queue are within that may be reused by a resource `node` uses first. On the node's own queue,
// queue order (plus the first-use barrier) is enough; other queues need a semaphore wait in G*.
inline QueueArray TransientPlacer::reusableUpTo(uint32_t node) const {
  constexpr uint32_t kAny = ~0u;
  if (state_.queueCount == 1) return {kAny, kAny, kAny};
  const QueueArray& known = state_.sync[node].known;
  const uint32_t own = state_.queueOf[node];
  // Chosen per queue rather than stored through `own` into the array (that store, reloaded at
  // once, stalled the walk), with a mask rather than a branch on the node's queue.
  auto limit = [&](uint32_t q) {
    const uint32_t any = 0u - static_cast<uint32_t>((q == own) | (q >= state_.queueCount));  // all ones: any
    return known[q] | any;
  };
  static_assert(kQueueClassCount == 3);
  return {limit(0), limit(1), limit(2)};
}

inline void TransientPlacer::place(uint32_t resource, uint32_t user) {
  ResolvedResource& resolved = state_.out.resources[resource];
  if (resolveRequirements_) requirements_.resolve(state_, resource, resolved);
  const MemoryRequirements& req = resolved.requirements;
  const uint32_t heapIndex = heapFor(resource, req.memoryTypeBits);
  Heap& heap = plan_.heaps[heapIndex];
  heap.alignment = std::max(heap.alignment, req.alignment);
  plan_.peakBytesUnaliased += alignUp(req.size, req.alignment);
  Placement& placement = plan_.placements[resource];
  placement.heap = heapIndex;
  placement.size = req.size;
  if (alias_ && takeFreeRange(free_[heapIndex], user, req, placement)) return;
  placement.offset = alignUp(heap.size, req.alignment);
  heap.size = placement.offset + req.size;
}

inline bool TransientPlacer::takeFreeRange(ScratchVector<FreeRange>& free, uint32_t user,
                                           const MemoryRequirements& req, Placement& placement) {
  const QueueArray limit = reusableUpTo(user);
  const uint64_t size = req.size;
  // The smallest range that fits (the first of equals): none can be smaller than an exact fit.
  FreeRange* const begin = free.data();
  FreeRange* const end = begin + free.size();
  FreeRange* best = nullptr;
  uint64_t bestSize = ~uint64_t{0};
  for (FreeRange* range = begin; range != end; ++range) {
    if (range->size < size || range->size >= bestSize) continue;  // cheap rejections first
    if (alignUp(range->offset, req.alignment) + size > range->offset + range->size) continue;
    if (range->lastSigma[0] > limit[0] || range->lastSigma[1] > limit[1] || range->lastSigma[2] > limit[2]) continue;
    best = range;
    bestSize = range->size;
    if (bestSize == size) break;
  }
  if (best == nullptr) return false;
  const uint64_t rangeStart = best->offset;
  const uint64_t rangeEnd = best->offset + best->size;
  placement.offset = alignUp(rangeStart, req.alignment);
  placement.aliasedAfterStages = best->stages[state_.queueOf[user]];
  // Padding before and the tail after stay free, still tagged with their last users: the chosen
  // entry becomes one of them (no copies of it on the way: see add() in stage_barriers.cpp).
  const uint64_t placedEnd = placement.offset + size;
  const bool head = placement.offset > rangeStart;
  const bool tail = placedEnd < rangeEnd;
  if (!head && !tail) {  // used up exactly: the last entry takes its place
    if (best != end - 1) *best = end[-1];
    free.pop_back();
    return true;
  }
  if (head) best->size = placement.offset - rangeStart;
  if (tail) {
    FreeRange* rest = best;
    if (head) {
      const auto index = static_cast<size_t>(best - begin);
      free.push_back(free[index]);  // (may move the array)
      rest = &free.back();
    }
    rest->offset = placedEnd;
    rest->size = rangeEnd - placedEnd;
  }
  return true;
}

inline void TransientPlacer::release(uint32_t resource, const QueueArray& lastSigma,
                                     const std::array<StageMask, kQueueClassCount>& stages) {
  const Placement& placement = plan_.placements[resource];
  FreeRange& range = free_[placement.heap].emplace_back();  // filled in place
  range.offset = placement.offset;
  range.size = placement.size;
  range.stages = stages;
  range.lastSigma = lastSigma;
}

}  // namespace fgb::graph::detail
