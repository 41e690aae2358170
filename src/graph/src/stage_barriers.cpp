// Stage: the barrier plan. Each alive resource's uses are walked in execution order while tracking
// its state (owning queue, layout, last write, reads since that write, what the write has been made
// visible to). Every hazard gets a barrier — RAW, WAR, WAW, layout changes — even when the layout
// does not change (same-layout WAW/RAW is a hazard too). A change of queue family becomes a
// release (after the last use on the old queue) plus an acquire (before the first use on the new
// one); the semaphore between them comes from G*. Transients start from UNDEFINED, waiting for the
// stages of earlier occupants of their memory on the same queue.
#include "compile_state.hpp"

namespace fgb::graph::detail {
namespace {

struct TrackedState {
  bool owned = false;  // false: transient before its first use (contents undefined)
  uint32_t queue = 0;
  Layout layout = Layout::Undefined;
  StageMask writeStages = kStageNone;
  AccessMask writeAccess = kAccessNone;
  StageMask readStages = kStageNone;     // reads since the last write
  StageMask visibleStages = kStageNone;  // the last write was made visible to these stages...
  AccessMask visibleAccess = kAccessNone;  // ...and accesses
  uint32_t lastStep = kInvalidIndex;
};

// A barrier waiting to be put in its slot: slot = step * 2 (+1 for "after the node").
struct PendingBarrier {
  uint32_t slot;
  Barrier barrier;
};

class BarrierPlanner {
 public:
  explicit BarrierPlanner(CompileState& state)
      : state_(state), start_(state.resourceUses.start), end_(state.resourceUses.end), uses_(state.resourceUses.uses) {}

  void run() {
    // Most uses get one barrier (transfers two, final states one more): size it once, not by doubling.
    pending_.reserve(uses_.size() + uses_.size() / 2);
    const auto& decls = state_.graph.resources();
    for (uint32_t r = 0; r < decls.size(); ++r) {
      if (state_.out.resourceAlive[r]) planResource(r);
    }
    emitIntoSteps();
  }

 private:
  [[nodiscard]] uint32_t familyOf(uint32_t queue) const { return state_.options.familyOfQueue[queue]; }

  void push(uint32_t step, bool after, const Barrier& barrier) {
    pending_.push_back({step * 2 + (after ? 1u : 0u), barrier});
  }

  TrackedState initialState(uint32_t resource) const {
    const ResourceDecl& decl = state_.graph.resources()[resource];
    TrackedState s;
    if (!decl.imported) return s;
    s.owned = true;
    s.queue = state_.options.queueOfClass[static_cast<size_t>(decl.initialState.queue)];
    s.layout = decl.initialState.layout;
    // What happened before the graph is treated as a write: later uses wait for it.
    s.writeStages = decl.initialState.stages;
    s.writeAccess = decl.initialState.access;
    return s;
  }

  // An imported resource whose first use in the graph overwrites it without reading needs no
  // ownership transfer in or out: Vulkan only asks for one when contents must survive the change
  // of queue family. Skipping both halves keeps repeated executions consistent (a release at the
  // end with no acquire, or an acquire with no release, is an error on the next execution).
  [[nodiscard]] bool discardsOnEntry(uint32_t resource) const {
    if (!state_.graph.resources()[resource].imported || start_[resource] == end_[resource]) return false;
    const MergedUse& first = uses_[start_[resource]];
    return first.writes && !first.reads;
  }

  void planResource(uint32_t resource) {
    const bool texture = state_.graph.resources()[resource].kind == ResourceKind::Texture;
    TrackedState s = initialState(resource);
    const bool discards = discardsOnEntry(resource);
    if (discards) {
      s.queue = state_.queueOf[uses_[start_[resource]].node];
      s.layout = Layout::Undefined;
    }
    for (uint32_t i = start_[resource]; i < end_[resource]; ++i) {
      const MergedUse& use = uses_[i];
      const uint32_t queue = state_.queueOf[use.node];
      const uint32_t step = state_.out.nodes[use.node].step;
      const Layout layout = texture ? use.layout : Layout::Undefined;
      // An ownership transfer or a layout change is a write in disguise (see advance()).
      const bool transitioned = s.owned && (familyOf(s.queue) != familyOf(queue) || (texture && layout != s.layout));
      if (!s.owned) {
        firstUse(resource, texture, use, queue, step);
      } else if (familyOf(s.queue) != familyOf(queue)) {
        transferOwnership(resource, s, use, queue, step, layout);
      } else {
        sameQueueHazard(resource, texture, s, use, queue, step, layout);
      }
      advance(s, use, queue, step, layout, transitioned);
    }
    finalState(resource, texture, s, discards);
  }

  void firstUse(uint32_t resource, bool texture, const MergedUse& use, uint32_t queue, uint32_t step) {
    const StageMask aliased = state_.out.aliasing.placements.empty()
                                  ? kStageNone
                                  : state_.out.aliasing.placements[resource].aliasedAfterStages;
    if (!texture && aliased == kStageNone) return;  // a fresh buffer needs no barrier
    Barrier b;
    b.resource = resource;
    b.srcStages = aliased;
    b.dstStages = use.stages;
    b.dstAccess = use.access;
    b.oldLayout = Layout::Undefined;
    b.newLayout = texture ? use.layout : Layout::Undefined;
    b.srcQueue = b.dstQueue = queue;
    push(step, false, b);
  }

  void transferOwnership(uint32_t resource, const TrackedState& s, const MergedUse& use, uint32_t queue,
                         uint32_t step, Layout layout) {
    Barrier release;
    release.kind = Barrier::Kind::Release;
    release.resource = resource;
    release.srcStages = s.writeStages | s.readStages;
    release.srcAccess = s.writeAccess;
    release.oldLayout = s.layout;
    release.newLayout = layout;
    release.srcQueue = s.queue;
    release.dstQueue = queue;
    Barrier acquire = release;
    acquire.kind = Barrier::Kind::Acquire;
    acquire.srcStages = kStageNone;
    acquire.srcAccess = kAccessNone;
    acquire.dstStages = use.stages;
    acquire.dstAccess = use.access;
    // An imported resource owned by another family before the graph was released by its owner;
    // only the acquire is ours then.
    if (s.lastStep != kInvalidIndex) push(s.lastStep, true, release);
    push(step, false, acquire);
  }

  void sameQueueHazard(uint32_t resource, bool texture, const TrackedState& s, const MergedUse& use,
                       uint32_t queue, uint32_t step, Layout layout) {
    const bool layoutChange = texture && layout != s.layout;
    Barrier b;
    b.resource = resource;
    b.oldLayout = texture ? s.layout : Layout::Undefined;
    b.newLayout = texture ? layout : Layout::Undefined;
    b.srcQueue = b.dstQueue = queue;
    b.dstStages = use.stages;
    b.dstAccess = use.access;
    if (use.writes || layoutChange) {
      // WAW/RAW(+write) wait for the last write, WAR for every read since it.
      b.srcStages = s.writeStages | s.readStages;
      b.srcAccess = s.writeAccess;
      if (b.srcStages == kStageNone && !layoutChange) return;
    } else {
      // Read after write: needed unless an earlier barrier already made the write visible here.
      const bool visible = (use.stages & ~s.visibleStages) == 0 && (use.access & ~s.visibleAccess) == 0;
      if (s.writeStages == kStageNone || visible) return;
      b.srcStages = s.writeStages;
      b.srcAccess = s.writeAccess;
    }
    push(step, false, b);
  }

  static void advance(TrackedState& s, const MergedUse& use, uint32_t queue, uint32_t step, Layout layout,
                      bool transitioned) {
    if (!use.writes && transitioned) {
      // The barrier just placed (layout transition / acquire) made the last write available and is
      // itself a write, ordered only before this use's stages. Later barriers must chain through
      // those stages (srcStages = them, srcAccess = none: nothing left to make available), not
      // name the original writer's stages, which would not chain (e.g. colour output -> compute).
      s.writeStages = use.stages;
      s.writeAccess = kAccessNone;
      s.readStages = use.stages;
      s.visibleStages = use.stages;
      s.visibleAccess = use.access;
    } else if (use.writes) {
      s.writeStages = use.stages;
      s.writeAccess = use.access & kWriteAccesses;
      s.readStages = kStageNone;
      s.visibleStages = kStageNone;
      s.visibleAccess = kAccessNone;
    } else {
      // Every read either got a barrier from the write or found the write already visible.
      s.readStages |= use.stages;
      s.visibleStages |= use.stages;
      s.visibleAccess |= use.access;
    }
    s.owned = true;
    s.queue = queue;
    s.layout = layout;
    s.lastStep = step;
  }

  void finalState(uint32_t resource, bool texture, const TrackedState& s, bool discardsOnEntry) {
    const ResourceDecl& decl = state_.graph.resources()[resource];
    if (!decl.imported || s.lastStep == kInvalidIndex) return;
    const ImportState& final = decl.finalState;
    const uint32_t finalQueue =
        discardsOnEntry ? s.queue : state_.options.queueOfClass[static_cast<size_t>(final.queue)];
    const Layout finalLayout = (!texture || final.layout == Layout::Undefined) ? s.layout : final.layout;
    const bool queueChange = familyOf(finalQueue) != familyOf(s.queue);
    if (!queueChange && finalLayout == s.layout && final.stages == kStageNone) return;
    Barrier b;
    b.kind = queueChange ? Barrier::Kind::Release : Barrier::Kind::Transition;
    b.resource = resource;
    b.srcStages = s.writeStages | s.readStages;
    b.srcAccess = s.writeAccess;
    b.dstStages = queueChange ? kStageNone : final.stages;
    b.dstAccess = queueChange ? kAccessNone : final.access;
    b.oldLayout = texture ? s.layout : Layout::Undefined;
    b.newLayout = texture ? finalLayout : Layout::Undefined;
    b.srcQueue = s.queue;
    b.dstQueue = finalQueue;
    push(s.lastStep, true, b);
  }

  // Stable counting sort of the pending barriers into per-step before/after ranges.
  void emitIntoSteps() {
    auto& steps = state_.out.steps;
    const auto slots = static_cast<uint32_t>(steps.size() * 2);
    ScratchVector<uint32_t> slotStart(slots + 1, 0);
    for (const PendingBarrier& p : pending_) ++slotStart[p.slot + 1];
    for (uint32_t i = 1; i <= slots; ++i) slotStart[i] += slotStart[i - 1];
    auto& barriers = state_.out.barriers;
    barriers.resize(pending_.size());
    ScratchVector<uint32_t> cursor(slotStart.begin(), slotStart.end() - 1);
    for (const PendingBarrier& p : pending_) barriers[cursor[p.slot]++] = p.barrier;
    for (uint32_t s = 0; s < steps.size(); ++s) {
      steps[s].before = {slotStart[2 * s], slotStart[2 * s + 1] - slotStart[2 * s]};
      steps[s].after = {slotStart[2 * s + 1], slotStart[2 * s + 2] - slotStart[2 * s + 1]};
    }
  }

  CompileState& state_;
  const ScratchVector<uint32_t>& start_;  // state.resourceUses (built by computeLifetimes)
  const ScratchVector<uint32_t>& end_;
  const ScratchVector<MergedUse>& uses_;
  ScratchVector<PendingBarrier> pending_;
};

}  // namespace

void planBarriers(CompileState& state) { BarrierPlanner(state).run(); }

}  // namespace fgb::graph::detail
