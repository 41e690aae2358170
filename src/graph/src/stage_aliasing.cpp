// Stage: transient memory aliasing by placement. A sweep over order positions places each
// transient when its lifetime starts and returns its range to a free list when it ends. A freed
// range remembers who used it last (per queue: the largest σ and the stages); a new resource may
// take it only if its first user is ordered after those users — same queue: by queue order plus the
// first-use barrier (which waits on the recorded stages); other queues: by a semaphore wait already
// in G* (the first user's `known` covers them). That is the lifetime "extended across queues until
// the consuming queue has waited". Buffers and images never share a heap, and resources share a
// heap only with identical memory-type bits, so placement needs no granularity or type checks.
#include "compile_state.hpp"

#include <algorithm>

namespace fgb::graph::detail {
namespace {

struct FreeRange {
  uint64_t offset = 0;
  uint64_t size = 0;
  QueueArray lastSigma{0, 0, 0};
  std::array<StageMask, kQueueClassCount> stages{kStageNone, kStageNone, kStageNone};
};

struct HeapState {
  ScratchVector<FreeRange> free;
};

uint64_t alignUp(uint64_t value, uint64_t alignment) {
  // Device alignments are powers of two: a mask instead of a 64-bit division on the hot path.
  if ((alignment & (alignment - 1)) == 0) return (value + alignment - 1) & ~(alignment - 1);
  return (value + alignment - 1) / alignment * alignment;
}

class Placer {
 public:
  Placer(CompileState& state, bool alias) : state_(state), plan_(state.out.aliasing), alias_(alias) {}

  void run() {
    const auto& decls = state_.graph.resources();
    const auto& lifetimes = state_.out.lifetimes;
    const auto positions = static_cast<uint32_t>(state_.out.order.size());
    plan_.placements.assign(decls.size(), {});
    // Bucket transients by the position where they start and end.
    ScratchVector<uint32_t> startsAt(positions + 1, 0), endsAt(positions + 1, 0);
    for (size_t r = 0; r < decls.size(); ++r) {
      if (!isPlaced(r)) continue;
      ++startsAt[lifetimes[r].first + 1];
      ++endsAt[lifetimes[r].last + 1];
    }
    for (uint32_t p = 1; p <= positions; ++p) {
      startsAt[p] += startsAt[p - 1];
      endsAt[p] += endsAt[p - 1];
    }
    ScratchVector<uint32_t> starting(startsAt.back(), 0), ending(endsAt.back(), 0);
    {
      ScratchVector<uint32_t> s(startsAt.begin(), startsAt.end() - 1), e(endsAt.begin(), endsAt.end() - 1);
      for (uint32_t r = 0; r < decls.size(); ++r) {
        if (!isPlaced(r)) continue;
        starting[s[lifetimes[r].first]++] = r;
        ending[e[lifetimes[r].last]++] = r;
      }
    }
    for (uint32_t p = 0; p < positions; ++p) {
      for (uint32_t i = startsAt[p]; i < startsAt[p + 1]; ++i) place(starting[i]);
      for (uint32_t i = endsAt[p]; i < endsAt[p + 1]; ++i) release(ending[i]);
    }
    plan_.peakBytesAliased = 0;
    for (const Heap& heap : plan_.heaps) plan_.peakBytesAliased += heap.size;
  }

 private:
  [[nodiscard]] bool isPlaced(size_t r) const {
    return !state_.graph.resources()[r].imported && state_.out.resourceAlive[r];
  }

  uint32_t heapFor(uint32_t resource) {
    const ResourceKind kind = state_.graph.resources()[resource].kind;
    const MemoryRequirements& req = state_.out.resources[resource].requirements;
    for (uint32_t h = 0; h < plan_.heaps.size(); ++h) {
      if (plan_.heaps[h].kind == kind && plan_.heaps[h].memoryTypeBits == req.memoryTypeBits) return h;
    }
    plan_.heaps.push_back({kind, req.memoryTypeBits, 0, 1});
    heaps_.emplace_back();
    return static_cast<uint32_t>(plan_.heaps.size() - 1);
  }

  // May `range` be reused by a resource whose first user is `node`?
  [[nodiscard]] bool orderedAfter(const FreeRange& range, uint32_t node) const {
    const uint32_t queue = state_.queueOf[node];
    for (uint32_t q = 0; q < state_.options.queueCount; ++q) {
      if (q != queue && range.lastSigma[q] > state_.known[node][q]) return false;
    }
    return true;
  }

  void place(uint32_t resource) {
    const MemoryRequirements& req = state_.out.resources[resource].requirements;
    const uint32_t heapIndex = heapFor(resource);
    Heap& heap = plan_.heaps[heapIndex];
    heap.alignment = std::max(heap.alignment, req.alignment);
    plan_.peakBytesUnaliased += alignUp(req.size, req.alignment);
    Placement& placement = plan_.placements[resource];
    placement.heap = heapIndex;
    placement.size = req.size;
    if (alias_ && takeFreeRange(heapIndex, resource, req, placement)) return;
    placement.offset = alignUp(heap.size, req.alignment);
    heap.size = placement.offset + req.size;
  }

  bool takeFreeRange(uint32_t heapIndex, uint32_t resource, const MemoryRequirements& req, Placement& placement) {
    auto& free = heaps_[heapIndex].free;
    const uint32_t user = state_.firstUser[resource];
    size_t best = free.size();
    for (size_t i = 0; i < free.size(); ++i) {
      const FreeRange& range = free[i];
      // Cheap rejections first: too small even unaligned, or no smaller than the best so far.
      if (range.size < req.size || (best != free.size() && range.size >= free[best].size)) continue;
      const uint64_t offset = alignUp(range.offset, req.alignment);
      if (offset + req.size > range.offset + range.size || !orderedAfter(range, user)) continue;
      best = i;  // smallest range that fits (first of equals)...
      if (range.size == req.size) break;  // ...and none can be smaller than an exact fit
    }
    if (best == free.size()) return false;
    const FreeRange taken = free[best];
    free[best] = free.back();
    free.pop_back();
    placement.offset = alignUp(taken.offset, req.alignment);
    placement.aliasedAfterStages = taken.stages[state_.queueOf[user]];
    // Padding before and the tail after stay free, still tagged with their last users.
    if (placement.offset > taken.offset) {
      FreeRange head = taken;
      head.size = placement.offset - taken.offset;
      free.push_back(head);
    }
    const uint64_t end = placement.offset + req.size;
    if (end < taken.offset + taken.size) {
      FreeRange tail = taken;
      tail.offset = end;
      tail.size = taken.offset + taken.size - end;
      free.push_back(tail);
    }
    return true;
  }

  void release(uint32_t resource) {
    const Placement& placement = plan_.placements[resource];
    FreeRange range{placement.offset, placement.size, {0, 0, 0}, {kStageNone, kStageNone, kStageNone}};
    for (uint32_t q = 0; q < kQueueClassCount; ++q) {
      range.lastSigma[q] = state_.lastSigmaOnQueue[resource * kQueueClassCount + q];
      range.stages[q] = state_.stagesOnQueue[resource * kQueueClassCount + q];
    }
    heaps_[placement.heap].free.push_back(range);
  }

  CompileState& state_;
  AliasingPlan& plan_;
  bool alias_;
  std::vector<HeapState> heaps_;
};

}  // namespace

void placeTransients(CompileState& state) {
  Placer(state, state.options.alias).run();
  // Fragmentation (mixed alignments, ranges that cannot merge) can make a placement worse than
  // none; then keep whichever of the two layouts is smaller.
  AliasingPlan& plan = state.out.aliasing;
  if (plan.peakBytesAliased > plan.peakBytesUnaliased) {
    AliasingPlan aliased = std::move(plan);
    plan = {};
    Placer(state, false).run();
    if (plan.peakBytesAliased > aliased.peakBytesAliased) plan = std::move(aliased);
  }
}

}  // namespace fgb::graph::detail
