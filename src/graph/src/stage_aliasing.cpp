// Stage: transient memory aliasing by placement. The walk over uses in execution order (in
// stage_barriers.cpp) places each transient at its first use and returns its range to a free list
// after its last. A freed range remembers who used it last (per queue: the largest σ and the
// stages); a new resource may take it only if its first user is ordered after those users — same
// queue: by queue order plus the first-use barrier (which waits on the recorded stages); other
// queues: by a semaphore wait already in G* (the first user's `known` covers them). That is the
// lifetime "extended across queues until the consuming queue has waited". Buffers and images never
// share a heap, and resources share a heap only with identical memory-type bits, so placement
// needs no granularity or type checks.
#include <algorithm>
#include <fgb/core/align.hpp>

#include "transient_placer.hpp"

namespace fgb::graph::detail {

TransientPlacer::TransientPlacer(CompileState& state, bool alias, bool resolveRequirements)
    : state_(state), plan_(state.out.aliasing), alias_(alias), resolveRequirements_(resolveRequirements) {
  plan_ = {};
  plan_.placements.assign(state.resourceCount, {});
}

void TransientPlacer::finish() {
  plan_.peakBytesAliased = 0;
  for (const Heap& heap : plan_.heaps) plan_.peakBytesAliased += heap.size;
}

uint32_t TransientPlacer::heapFor(ResourceKind kind, uint32_t memoryTypeBits) {
  for (uint32_t h = 0; h < plan_.heaps.size(); ++h) {
    if (plan_.heaps[h].kind == kind && plan_.heaps[h].memoryTypeBits == memoryTypeBits) return h;
  }
  plan_.heaps.push_back({kind, memoryTypeBits, 0, 1});
  free_.emplace_back();
  return static_cast<uint32_t>(plan_.heaps.size()) - 1;
}

void TransientPlacer::place(uint32_t resource, uint32_t user) {
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
  heap.size = placement.offset + req.size;
}

// Whether `user`, starting, is ordered after every last user of `range`: on its own queue by queue
// order; on the others, by a semaphore wait it already knows of (see CompileState::known).
bool TransientPlacer::reusableBy(const FreeRange& range, uint32_t user) const {
  if (state_.queueCount == 1) return true;
  for (uint32_t q = 0; q < state_.queueCount; ++q) {
    if (q != state_.queueOf[user] && range.lastSigma[q] > state_.known[user][q]) return false;
  }
  return true;
}

// Takes the smallest free range that fits (the first of equals) for `placement`. What is left of
// the range before and after the placed resource stays free, still tagged with its last users.
bool TransientPlacer::takeFreeRange(std::vector<FreeRange>& free, uint32_t user, const MemoryRequirements& req,
                                    Placement& placement) {
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

void TransientPlacer::release(uint32_t resource, const QueueArray& lastSigma, const QueueStages& stages) {
  const Placement& placement = plan_.placements[resource];
  free_[placement.heap].push_back({placement.offset, placement.size, lastSigma, stages});
}

}  // namespace fgb::graph::detail
