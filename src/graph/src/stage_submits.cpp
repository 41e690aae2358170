// Stage: steps and submits. Each queue's nodes (in order) are cut into submits at dependency-level
// boundaries: a submit ends after a level holding a G* source on that queue (so the wait can be
// signalled early) and a new one begins at a level holding a G* target (the wait blocks the submit
// from its start). Every submit signals its 1-based index on the queue's timeline; waits only ever
// point at submits that end at a strictly lower level, so no submit order can deadlock.
#include "compile_state.hpp"

#include <algorithm>

namespace fgb::graph::detail {

void placeSubmits(CompileState& state) {
  CompiledGraph& out = state.out;
  const uint32_t queues = state.options.queueCount;
  ScratchVector<uint8_t> isSource(state.nodeCount, 0);
  ScratchVector<uint8_t> isTarget(state.nodeCount, 0);
  for (const Edge& e : out.syncEdges) {
    isSource[e.from] = 1;
    isTarget[e.to] = 1;
  }

  out.submitsPerQueue.assign(queues, 0);
  out.steps.reserve(out.order.size());
  ScratchVector<uint32_t> onQueue;
  for (uint32_t queue = 0; queue < queues; ++queue) {
    onQueue.clear();
    for (const uint32_t n : out.order) {
      if (state.queueOf[n] == queue) onQueue.push_back(n);
    }
    uint64_t signal = 0;
    bool open = false;
    auto closeSubmit = [&] {
      if (open) out.submits.back().stepCount = static_cast<uint32_t>(out.steps.size()) - out.submits.back().firstStep;
      open = false;
    };
    for (size_t begin = 0; begin < onQueue.size();) {
      const uint32_t level = out.nodes[onQueue[begin]].level;
      size_t end = begin;
      bool levelHasTarget = false;
      bool levelHasSource = false;
      while (end < onQueue.size() && out.nodes[onQueue[end]].level == level) {
        levelHasTarget |= isTarget[onQueue[end]] != 0;
        levelHasSource |= isSource[onQueue[end]] != 0;
        ++end;
      }
      if (levelHasTarget) closeSubmit();
      if (!open) {
        out.submits.push_back({queue, static_cast<uint32_t>(out.steps.size()), 0, {}, ++signal});
        open = true;
      }
      for (size_t i = begin; i < end; ++i) {
        const uint32_t n = onQueue[i];
        out.nodes[n].step = static_cast<uint32_t>(out.steps.size());
        out.nodes[n].submit = static_cast<uint32_t>(out.submits.size() - 1);
        out.steps.push_back({n, {}, {}});
      }
      if (levelHasSource) closeSubmit();
      begin = end;
    }
    closeSubmit();
    out.submitsPerQueue[queue] = static_cast<uint32_t>(signal);
  }

  // Waits: one per (submit, source queue), on the latest submit needed.
  for (const Edge& e : out.syncEdges) {
    Submit& target = out.submits[out.nodes[e.to].submit];
    const Submit& source = out.submits[out.nodes[e.from].submit];
    auto existing = std::find_if(target.waits.begin(), target.waits.end(),
                                 [&](const SemaphoreWait& w) { return w.queue == source.queue; });
    if (existing == target.waits.end()) {
      target.waits.push_back({source.queue, source.signalValue, kStageAllCommands});
    } else if (existing->value < source.signalValue) {
      existing->value = source.signalValue;
    }
  }
}

}  // namespace fgb::graph::detail
