// Internal: transient memory aliasing by placement, driven by the walk over uses in execution order
// that also plans the barriers (stage_barriers.cpp). The walk places each transient at its first
// use and returns its range to a free list after its last. A freed range remembers who used it last
// (per queue: the largest σ and the stages); a new resource may take it only if its first user is
// ordered after those users — same queue: by queue order plus the first-use barrier (which waits on
// the recorded stages); other queues: by a semaphore wait already in G* (the first user's `known`
// covers them). That is the lifetime "extended across queues until the consuming queue has
// waited". Buffers and images never share a heap, and resources share a heap only with identical
// memory-type bits, so placement needs no granularity or type checks.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <fgb/core/align.hpp>
#include <vector>

#include "compile_state.hpp"

namespace fgb::graph::detail {

using QueueStages = std::array<StageMask, kQueueClassCount>;
using QueueAccesses = std::array<AccessMask, kQueueClassCount>;

class TransientPlacer {
 public:
  // Starts an empty plan in state.out.aliasing; with `alias` false, nothing shares memory. With
  // `resolveRequirements`, each transient's memory requirements are resolved as it is placed (a
  // second walk over the same compile reuses them).
  TransientPlacer(CompileState& state, bool alias, bool resolveRequirements)
      : state_(state), plan_(state.out.aliasing), alias_(alias), resolveRequirements_(resolveRequirements) {
    plan_ = {};
    plan_.placements.assign(state.resourceCount, {});
  }

  // Places a transient at its first use, by `user` (the node being walked).
  void place(uint32_t resource, uint32_t user) {
    ResolvedResource& resolved = state_.out.resources[resource];
    if (resolveRequirements_) {
      const ResourceDecl& decl = state_.resource(resource);
      resolved.requirements = state_.options.requirements ? state_.options.requirements(decl, resolved)
                                                          : estimateRequirements(decl, resolved);
      resolved.requirements.alignment = std::max<uint64_t>(resolved.requirements.alignment, 1);
    }
    const MemoryRequirements& req = resolved.requirements;
    const uint32_t heapIndex = heapFor(state_.resource(resource).kind, req.memoryTypeBits);
    Heap& heap = plan_.heaps[heapIndex];
    heap.alignment = std::max(heap.alignment, req.alignment);
    plan_.peakBytesUnaliased += alignUp(req.size, req.alignment);
    Placement& placement = plan_.placements[resource];
    placement.heap = heapIndex;
    placement.size = req.size;
    if (alias_ && takeFreeRange(free_[heapIndex], user, req, placement)) return;
    placement.offset = alignUp(heap.size, req.alignment);
    plan_.peakBytesAliased += placement.offset + req.size - heap.size;  // the sum of the heaps' sizes
    heap.size = placement.offset + req.size;
  }

  // Hands its range back after its last user; later occupants wait for what the users did (on
  // each queue: the largest σ of a user, the stages used and the writes made).
  void release(uint32_t resource, const QueueArray& lastSigma, const QueueStages& stages,
               const QueueAccesses& writes) {
    const Placement& placement = plan_.placements[resource];
    free_[placement.heap].push_back({placement.offset, placement.size, lastSigma, stages, writes});
  }

 private:
  // A range of a heap nobody uses any more, with who used it last (per queue: the largest σ, the
  // stages and the writes).
  struct FreeRange {
    uint64_t offset;
    uint64_t size;
    QueueArray lastSigma;
    QueueStages stages;
    QueueAccesses writes;
  };

  uint32_t heapFor(ResourceKind kind, uint32_t memoryTypeBits) {
    for (uint32_t h = 0; h < plan_.heaps.size(); ++h) {
      if (plan_.heaps[h].kind == kind && plan_.heaps[h].memoryTypeBits == memoryTypeBits) return h;
    }
    plan_.heaps.push_back({kind, memoryTypeBits, 0, 1});
    free_.emplace_back();
    return static_cast<uint32_t>(plan_.heaps.size()) - 1;
  }

  // Whether `user`, starting, is ordered after every last user of `range`: on its own queue by
  // queue order; on the others, by a semaphore wait it already knows of (see CompileState::known).
  [[nodiscard]] bool reusableBy(const FreeRange& range, uint32_t user) const {
    if (state_.queueCount == 1) return true;
    for (uint32_t q = 0; q < state_.queueCount; ++q) {
      if (q != state_.queueOf[user] && range.lastSigma[q] > state_.known[user][q]) return false;
    }
    return true;
  }

  // Takes the smallest free range that fits (the first of equals) for `placement`. What is left of
  // the range before and after the placed resource stays free, still tagged with its last users.
  bool takeFreeRange(std::vector<FreeRange>& free, uint32_t user, const MemoryRequirements& req, Placement& placement) {
    size_t best = free.size();
    for (size_t i = 0; i < free.size(); ++i) {
      const FreeRange& range = free[i];
      if (range.size < req.size || (best < free.size() && range.size >= free[best].size)) continue;
      if (alignUp(range.offset, req.alignment) + req.size > range.offset + range.size) continue;
      if (reusableBy(range, user)) best = i;
    }
    if (best == free.size()) return false;
    const uint64_t rangeStart = free[best].offset;
    const uint64_t rangeEnd = free[best].offset + free[best].size;
    placement.offset = alignUp(rangeStart, req.alignment);
    placement.aliasedAfterStages = free[best].stages[state_.queueOf[user]];
    placement.aliasedAfterWrites = free[best].writes[state_.queueOf[user]];
    const uint64_t placedEnd = placement.offset + req.size;
    const bool head = placement.offset > rangeStart;
    const bool tail = placedEnd < rangeEnd;
    if (!head && !tail) {  // used up exactly: the last entry takes its place
      free[best] = free.back();
      free.pop_back();
      return true;
    }
    if (head) free[best].size = placement.offset - rangeStart;
    if (tail) {
      if (head) free.push_back(free[best]);  // the tail becomes a range of its own
      FreeRange& rest = head ? free.back() : free[best];
      rest.offset = placedEnd;
      rest.size = rangeEnd - placedEnd;
    }
    return true;
  }

  CompileState& state_;
  AliasingPlan& plan_;
  bool alias_;
  bool resolveRequirements_;
  std::vector<std::vector<FreeRange>> free_;  // per heap
};

}  // namespace fgb::graph::detail
