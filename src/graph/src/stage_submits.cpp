// Stage: steps and submits. Each queue's nodes (in order) are cut into submits at dependency-level
// boundaries: a submit ends after a level holding a G* source on that queue (so the wait can be
// signalled early) and a new one begins at a level holding a G* target (the wait blocks the submit
// from its start). Every submit signals its 1-based index on the queue's timeline; waits only ever
// point at submits that end at a strictly lower level, so no submit order can deadlock.
#include <algorithm>

#include "compile_state.hpp"

namespace fgb::graph::detail {
namespace {

enum SyncRole : uint8_t { kSyncSource = 1u << 0, kSyncTarget = 1u << 1 };

// Steps: the order, grouped by queue (a stable counting sort); returns where each queue's steps begin.
std::vector<uint32_t> groupStepsByQueue(CompileState& state) {
  CompiledGraph& out = state.out;
  std::vector<uint32_t> queueStart(state.queueCount + 1, 0);
  for (const uint32_t n : out.order) ++queueStart[state.queueOf[n] + 1];
  for (uint32_t q = 1; q <= state.queueCount; ++q) queueStart[q] += queueStart[q - 1];
  out.steps.resize(out.order.size());
  std::vector<uint32_t> cursor(queueStart.begin(), queueStart.end() - 1);
  for (const uint32_t n : out.order) {
    const uint32_t step = cursor[state.queueOf[n]]++;
    out.steps[step].node = n;
    out.nodes[n].step = step;
  }
  return queueStart;
}

// Each queue's steps cut into submits at level boundaries (see the top of this file).
void cutSubmits(CompileState& state, const std::vector<uint32_t>& queueStart) {
  CompiledGraph& out = state.out;
  // Per (queue, level): the sync roles of the queue's nodes at that level.
  const uint32_t levels = state.maxLevel + 1;
  std::vector<uint8_t> rolesAt(static_cast<size_t>(state.queueCount) * levels, 0);
  for (const Edge& e : out.syncEdges) {
    rolesAt[(state.queueOf[e.from] * levels) + out.nodes[e.from].level] |= kSyncSource;
    rolesAt[(state.queueOf[e.to] * levels) + out.nodes[e.to].level] |= kSyncTarget;
  }
  for (uint32_t queue = 0; queue < state.queueCount; ++queue) {
    const uint8_t* roles = &rolesAt[static_cast<size_t>(queue) * levels];
    uint32_t previousLevel = 0;
    for (uint32_t step = queueStart[queue]; step < queueStart[queue + 1]; ++step) {
      const uint32_t node = out.steps[step].node;
      const uint32_t level = out.nodes[node].level;
      // A new level starts a submit if the last one held a G* source or this one holds a G* target.
      const bool cut =
          level != previousLevel && ((roles[previousLevel] & kSyncSource) != 0 || (roles[level] & kSyncTarget) != 0);
      if (step == queueStart[queue] || cut) {
        ++out.submitsPerQueue[queue];
        out.submits.push_back({queue, step, 0, {}, out.submitsPerQueue[queue]});
      }
      ++out.submits.back().stepCount;
      out.nodes[node].submit = static_cast<uint32_t>(out.submits.size()) - 1;
      previousLevel = level;
    }
  }
}

// Waits: one per (submit, source queue), on the latest submit needed.
void addWaits(CompiledGraph& out) {
  for (const Edge& e : out.syncEdges) {
    Submit& target = out.submits[out.nodes[e.to].submit];
    const Submit& source = out.submits[out.nodes[e.from].submit];
    const auto existing = std::find_if(target.waits.begin(), target.waits.end(),
                                       [&](const SemaphoreWait& wait) { return wait.queue == source.queue; });
    if (existing == target.waits.end()) {
      target.waits.push_back({source.queue, source.signalValue, kStageAllCommands});
    } else {
      existing->value = std::max(existing->value, source.signalValue);
    }
  }
}

}  // namespace

void placeSubmits(CompileState& state) {
  const std::vector<uint32_t> queueStart = groupStepsByQueue(state);
  state.out.submits.clear();
  state.out.submitsPerQueue.assign(state.queueCount, 0);
  cutSubmits(state, queueStart);
  addWaits(state.out);
}

}  // namespace fgb::graph::detail
