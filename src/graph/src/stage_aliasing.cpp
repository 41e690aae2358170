// Stage: transient memory aliasing by placement. The walk over uses in execution order (in
// stage_barriers.cpp) places each transient at its first use and returns its range to a free list
// after its last. A freed range remembers who used it last (per queue: the largest σ and the
// stages); a new resource may take it only if its first user is ordered after those users — same
// queue: by queue order plus the first-use barrier (which waits on the recorded stages); other
// queues: by a semaphore wait already in G* (the first user's `known` covers them). That is the
// lifetime "extended across queues until the consuming queue has waited". Buffers and images never
// share a heap, and resources share a heap only with identical memory-type bits, so placement
// needs no granularity or type checks. What the walk does per transient (place, release) is in
// transient_placer.hpp, inline; here is what it does once per heap or per walk.
#include "transient_placer.hpp"

namespace fgb::graph::detail {

TransientPlacer::TransientPlacer(CompileState& state, bool alias, bool resolveRequirements)
    : state_(state), plan_(state.out.aliasing), alias_(alias), resolveRequirements_(resolveRequirements) {
  plan_.placements.assign(state.resourceCount, {});
  plan_.heaps.clear();
  plan_.peakBytesAliased = 0;
  plan_.peakBytesUnaliased = 0;
}

void TransientPlacer::finish() {
  plan_.peakBytesAliased = 0;
  for (const Heap& heap : plan_.heaps) plan_.peakBytesAliased += heap.size;
}

uint32_t TransientPlacer::findOrAddHeap(ResourceKind kind, uint32_t memoryTypeBits) {
  for (lastHeap_ = 0; lastHeap_ < plan_.heaps.size(); ++lastHeap_) {
    const Heap& heap = plan_.heaps[lastHeap_];
    if (heap.kind == kind && heap.memoryTypeBits == memoryTypeBits) return lastHeap_;
  }
  plan_.heaps.push_back({kind, memoryTypeBits, 0, 1});
  free_.emplace_back();
  return lastHeap_;
}

}  // namespace fgb::graph::detail
