// Internal: transient memory aliasing by placement, driven by the walk over uses in execution
// order that also plans the barriers (stage_barriers.cpp). The rules are in stage_aliasing.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "compile_state.hpp"

namespace fgb::graph::detail {

using QueueStages = std::array<StageMask, kQueueClassCount>;

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
  void release(uint32_t resource, const QueueArray& lastSigma, const QueueStages& stages);
  // Sums the heap sizes into the plan's peak once every transient was placed and released.
  void finish();

 private:
  // A range of a heap nobody uses any more, with who used it last (per queue: the largest σ and
  // the stages).
  struct FreeRange {
    uint64_t offset;
    uint64_t size;
    QueueArray lastSigma;
    QueueStages stages;
  };

  uint32_t heapFor(ResourceKind kind, uint32_t memoryTypeBits);
  [[nodiscard]] bool reusableBy(const FreeRange& range, uint32_t user) const;
  bool takeFreeRange(std::vector<FreeRange>& free, uint32_t user, const MemoryRequirements& req, Placement& placement);

  CompileState& state_;
  AliasingPlan& plan_;
  bool alias_;
  bool resolveRequirements_;
  std::vector<std::vector<FreeRange>> free_;  // per heap
};

}  // namespace fgb::graph::detail
