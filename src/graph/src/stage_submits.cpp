// Stage: steps and submits. Each queue's nodes (in order) are cut into submits at dependency-level
// boundaries: a submit ends after a level holding a G* source on that queue (so the wait can be
// signalled early) and a new one begins at a level holding a G* target (the wait blocks the submit
// from its start). Every submit signals its 1-based index on the queue's timeline; waits only ever
// point at submits that end at a strictly lower level, so no submit order can deadlock.
#include "compile_state.hpp"

#include <algorithm>

namespace fgb::graph::detail {

namespace {

enum SyncRole : uint8_t { kSyncSource = 1u << 0, kSyncTarget = 1u << 1 };

// Steps: the order, grouped by queue (a stable counting sort); returns where each queue's steps begin.
ScratchVector<uint32_t> groupStepsByQueue(CompileState& state) {
  CompiledGraph& out = state.out;
  ScratchVector<uint32_t> queueStart(state.queueCount + 1, 0);
  for (const uint32_t n : out.order) ++queueStart[state.queueOf[n] + 1];
  for (uint32_t q = 1; q <= state.queueCount; ++q) queueStart[q] += queueStart[q - 1];
  out.steps.resize(out.order.size());
  ScratchVector<uint32_t> cursor(queueStart.begin(), queueStart.end() - 1);
  for (const uint32_t n : out.order) {
    const uint32_t step = cursor[state.queueOf[n]]++;
    out.steps[step].node = n;
    out.nodes[n].step = step;
  }
  return queueStart;
}

// out.submits may hold the submits of an earlier compile (see ~CompiledGraph): they are
// overwritten one by one, keeping the capacity of their wait lists, and the rest dropped (finish).
class SubmitList {
 public:
  explicit SubmitList(CompiledGraph& out) : out_(out) {}

  void open(uint32_t queue, uint32_t firstStep, uint32_t stepCount, uint64_t signal) {
    if (count_ == out_.submits.size()) out_.submits.emplace_back();
    Submit& submit = out_.submits[count_++];
    submit.queue = queue;
    submit.firstStep = firstStep;
    submit.stepCount = stepCount;
    submit.waits.clear();
    submit.signalValue = signal;
  }
  [[nodiscard]] uint32_t lastIndex() const { return count_ - 1; }
  void finish() { out_.submits.resize(count_); }

 private:
  CompiledGraph& out_;
  uint32_t count_ = 0;
};

// Without sync edges no queue waits for another, so nothing ends a submit early or starts one late:
// each queue's steps are one submit. (The general cut below would find the same, level by level.)
void placeOneSubmitPerQueue(CompileState& state, const ScratchVector<uint32_t>& queueStart, SubmitList& submits) {
  CompiledGraph& out = state.out;
  for (uint32_t queue = 0; queue < state.queueCount; ++queue) {
    const uint32_t begin = queueStart[queue];
    const uint32_t end = queueStart[queue + 1];
    if (begin == end) continue;
    submits.open(queue, begin, end - begin, 1);
    for (uint32_t step = begin; step < end; ++step) out.nodes[out.steps[step].node].submit = submits.lastIndex();
    out.submitsPerQueue[queue] = 1;
  }
}

// Each queue's steps cut into submits at level boundaries (see the top of this file). The cut is
// computed without branches: whether a step starts a submit depends on the graph's shape step by
// step, and as branches those tests are mispredicted about as often as not.
void cutSubmitsAtSyncLevels(CompileState& state, const ScratchVector<uint32_t>& queueStart, SubmitList& submits) {
  CompiledGraph& out = state.out;
  // Per (queue, level): the sync roles of the queue's nodes at that level.
  const uint32_t levels = state.maxLevel + 1;
  ScratchVector<uint8_t> rolesAt(static_cast<size_t>(state.queueCount) * levels, 0);
  for (const Edge& e : out.syncEdges) {
    rolesAt[(state.queueOf[e.from] * levels) + state.level[e.from]] |= kSyncSource;
    rolesAt[(state.queueOf[e.to] * levels) + state.level[e.to]] |= kSyncTarget;
  }
  ScratchVector<uint32_t> submitStart(out.steps.size() + 1, 0);  // per submit: its first step
  uint32_t submitCount = 0;
  for (uint32_t queue = 0; queue < state.queueCount; ++queue) {
    const uint32_t begin = queueStart[queue];
    const uint32_t end = queueStart[queue + 1];
    if (begin == end) continue;
    const uint8_t* roles = &rolesAt[static_cast<size_t>(queue) * levels];
    const uint32_t firstSubmit = submitCount;
    submitStart[submitCount++] = begin;
    uint32_t previousLevel = state.level[out.steps[begin].node];
    for (uint32_t step = begin; step < end; ++step) {
      const uint32_t node = out.steps[step].node;
      const uint32_t level = state.level[node];
      // A new level starts a submit if the last one held a G* source or this one holds a G* target.
      const uint32_t sourceBefore = roles[previousLevel] & kSyncSource;
      const uint32_t targetHere = (roles[level] & kSyncTarget) >> 1;
      const uint32_t cut = static_cast<uint32_t>(level != previousLevel) & (sourceBefore | targetHere);
      submitStart[submitCount] = step;
      submitCount += cut;
      out.nodes[node].submit = submitCount - 1;
      previousLevel = level;
    }
    submitStart[submitCount] = end;
    for (uint32_t submit = firstSubmit; submit < submitCount; ++submit) {
      submits.open(queue, submitStart[submit], submitStart[submit + 1] - submitStart[submit], submit - firstSubmit + 1);
    }
    out.submitsPerQueue[queue] = submitCount - firstSubmit;
  }
}

// Waits: one per (submit, source queue), on the latest submit needed. (A plain loop finds the
// wait on the queue: std::find_if's unrolled form ends in a jump on the list's length, 0 to 2 here
// and as good as random, which was mispredicted for about every other edge.)
void addWaits(CompiledGraph& out) {
  for (const Edge& e : out.syncEdges) {
    Submit& target = out.submits[out.nodes[e.to].submit];
    const Submit& source = out.submits[out.nodes[e.from].submit];
    SemaphoreWait* existing = nullptr;
    for (SemaphoreWait& wait : target.waits) {
      if (wait.queue == source.queue) existing = &wait;
    }
    if (existing == nullptr) {
      target.waits.push_back({source.queue, source.signalValue, kStageAllCommands});
    } else if (existing->value < source.signalValue) {
      existing->value = source.signalValue;
    }
  }
}

}  // namespace

void placeSubmits(CompileState& state) {
  const ScratchVector<uint32_t> queueStart = groupStepsByQueue(state);
  state.out.submitsPerQueue.assign(state.queueCount, 0);
  SubmitList submits(state.out);
  if (state.out.syncEdges.empty()) {
    placeOneSubmitPerQueue(state, queueStart, submits);
  } else {
    cutSubmitsAtSyncLevels(state, queueStart, submits);
  }
  submits.finish();
  addWaits(state.out);
}

}  // namespace fgb::graph::detail
