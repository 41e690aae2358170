// Internal: transient memory aliasing by placement, driven by the walk over uses in execution
// order that also plans the barriers (see stage_barriers.cpp; implemented in stage_aliasing.cpp).
#pragma once

#include "compile_state.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace fgb::graph::detail {

class TransientPlacer {
 public:
  // Starts an empty plan in state.out.aliasing; with `alias` false, nothing shares memory.
  TransientPlacer(CompileState& state, bool alias);

  // Places a transient at its first use (its first user is the node being walked).
  void place(uint32_t resource);
  // Hands its range back after its last user; later occupants wait for what the users did.
  void release(uint32_t resource);
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
  bool takeFreeRange(ScratchVector<FreeRange>& free, uint32_t resource, const MemoryRequirements& req,
                     Placement& placement);

  CompileState& state_;
  AliasingPlan& plan_;
  bool alias_;
  uint32_t lastHeap_ = 0;                       // the heap the last transient went to
  std::vector<ScratchVector<FreeRange>> free_;  // per heap
};

}  // namespace fgb::graph::detail
