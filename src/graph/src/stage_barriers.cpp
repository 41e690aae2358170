// Stage: memory placement and the barrier plan, in one walk over the alive uses in execution order
// (a transient's first barrier waits for the earlier occupants of the memory it was placed in).
//
// Barriers: each resource's uses are walked in execution order while tracking its state (owning
// queue, layout, last write, reads since that write, what the write has been made visible to).
// Every hazard gets a barrier — RAW, WAR, WAW, layout changes — even when the layout
// does not change (same-layout WAW/RAW is a hazard too). A change of queue family becomes a
// release (after the last use on the old queue) plus an acquire (before the first use on the new
// one); the semaphore between them comes from G*. Transients start from UNDEFINED, waiting for the
// stages of earlier occupants of their memory on the same queue.
#include <algorithm>
#include <span>
#include <utility>

#include "transient_placer.hpp"

namespace fgb::graph::detail {
namespace {

// A resource's state between its uses. Set at its first use (see BarrierPlanner::planUse).
struct TrackedState {
  bool discardsOnEntry = false;  // imported, but first overwritten without being read (see enterImport)
  Layout layout = Layout::Undefined;
  uint32_t queue = 0;
  StageMask writeStages = kStageNone;  // the last write (or what stands for it: see advance)
  AccessMask writeAccess = kAccessNone;
  StageMask readStages = kStageNone;       // reads since the last write
  StageMask visibleStages = kStageNone;    // the last write was made visible to these stages...
  AccessMask visibleAccess = kAccessNone;  // ...and accesses
  uint32_t lastStep = kInvalidIndex;       // the step of the last use (none before the graph)
};

// One side of a barrier: what it waits for (source) or what waits for it (destination).
struct Side {
  StageMask stages;
  AccessMask access;
  Layout layout;
  uint32_t queue;
};

Barrier barrier(Barrier::Kind kind, uint32_t resource, const Side& src, const Side& dst) {
  return {kind, resource, src.stages, src.access, dst.stages, dst.access, src.layout, dst.layout, src.queue, dst.queue};
}

// Tracks the state of each resource through its uses, in execution order, and records the
// barriers each use needs. Barriers before a node are all found while its uses are walked, so they
// go straight to the output, each step's run where the walk reached it. Barriers after a node
// (ownership releases, found at a later node's use; final states of imports) are kept apart and
// appended grouped by step at the end.
class BarrierPlanner {
 public:
  explicit BarrierPlanner(CompileState& state)
      : state_(state), states_(state.resourceCount), after_(state.out.steps.size()) {
    state.out.barriers.clear();
  }

  // The uses that follow are the node's; endNode() closes its range of barriers before it.
  void beginNode(uint32_t node) {
    queue_ = state_.queueOf[node];
    step_ = state_.out.nodes[node].step;
    firstBefore_ = static_cast<uint32_t>(state_.out.barriers.size());
  }
  void endNode() {
    state_.out.steps[step_].before = {firstBefore_, static_cast<uint32_t>(state_.out.barriers.size()) - firstBefore_};
  }

  void planUse(const Use& use, bool firstUse) {
    const uint32_t resource = use.resource;
    const bool texture = state_.isTexture(resource);
    TrackedState& s = states_[resource];
    if (firstUse) s = state_.isImported(resource) ? enterImport(use) : enterTransient(resource);
    const Layout layout = texture ? use.layout : Layout::Undefined;
    // An ownership transfer or a layout change is a write in disguise (see advance()).
    const bool ownerChanges = changesOwner(s.queue, queue_, texture);
    const bool transitioned = ownerChanges || (texture && layout != s.layout);
    if (ownerChanges) {
      transferOwnership(resource, s, use, layout);
    } else if (handsOverSharedBuffer(s.queue, queue_, texture)) {
      handOverSharedBuffer(s);
    } else {
      sameQueueHazard(resource, texture, s, use, layout);
    }
    advance(s, use, layout, transitioned);
  }

  // After an imported resource's last use: back to the state the declaration asked for.
  void finalState(uint32_t resource) {
    const TrackedState& s = states_[resource];
    const bool texture = state_.isTexture(resource);
    const ImportState& final = state_.resource(resource).finalState;
    const uint32_t declaredFinalQueue = state_.options.queueOfClass[static_cast<size_t>(final.queue)];
    const uint32_t finalQueue = s.discardsOnEntry ? s.queue : declaredFinalQueue;
    const Layout finalLayout = (!texture || final.layout == Layout::Undefined) ? s.layout : final.layout;
    const bool queueChange = changesOwner(s.queue, finalQueue, texture);
    // A shared buffer that ends on another queue is handed over like one between nodes: whatever
    // uses it next there waits on a semaphore, which makes the writes visible. Only availability to
    // the host is left to a barrier here, and it must name no stage of the other queue (a
    // transfer-only family has no vertex or fragment stages).
    const bool handedOver = handsOverSharedBuffer(s.queue, declaredFinalQueue, texture);
    const StageMask stagesKept = handedOver ? StageMask{kStageHost} : ~StageMask{0};
    const AccessMask accessKept = handedOver ? AccessMask{kAccessHostRead | kAccessHostWrite} : ~AccessMask{0};
    const StageMask dstStages = queueChange ? kStageNone : final.stages & stagesKept;
    const AccessMask dstAccess = queueChange ? kAccessNone : final.access & accessKept;
    if (!queueChange && finalLayout == s.layout && dstStages == kStageNone) return;
    addAfter(
        s.lastStep,
        barrier(queueChange ? Barrier::Kind::Release : Barrier::Kind::Transition, resource,
                {s.writeStages | s.readStages, s.writeAccess, texture ? s.layout : Layout::Undefined, s.queue},
                {dstStages, dstAccess, texture ? finalLayout : Layout::Undefined, handedOver ? s.queue : finalQueue}));
  }

  // Appends the barriers after steps to the output, step by step (in the order found within a
  // step), and sets each step's after-range.
  void emitAfterBarriers() {
    std::vector<Barrier>& barriers = state_.out.barriers;
    for (uint32_t step = 0; step < after_.size(); ++step) {
      const auto first = static_cast<uint32_t>(barriers.size());
      barriers.insert(barriers.end(), after_[step].begin(), after_[step].end());
      state_.out.steps[step].after = {first, static_cast<uint32_t>(after_[step].size())};
    }
  }

 private:
  // Whether moving a resource between these queues is a queue-family ownership transfer. Buffers
  // shared by every family (CompileOptions::buffersShareFamilies) never need one.
  [[nodiscard]] bool changesOwner(uint32_t from, uint32_t to, bool texture) const {
    const auto& families = state_.options.familyOfQueue;
    return (texture || !state_.options.buffersShareFamilies) && families[from] != families[to];
  }
  // Whether moving a resource between these queues hands a shared buffer over (see
  // handOverSharedBuffer): a semaphore orders and makes visible what crosses, not a barrier.
  [[nodiscard]] bool handsOverSharedBuffer(uint32_t from, uint32_t to, bool texture) const {
    return !texture && state_.options.buffersShareFamilies && from != to;
  }

  void addBefore(const Barrier& barrier) { state_.out.barriers.push_back(barrier); }
  void addAfter(uint32_t step, const Barrier& barrier) { after_[step].push_back(barrier); }

  // An imported resource's state as the graph finds it.
  [[nodiscard]] TrackedState enterImport(const Use& first) const {
    // An imported resource whose first use in the graph overwrites it without reading needs no
    // ownership transfer in or out: Vulkan only asks for one when contents must survive the change
    // of queue family. Skipping both halves keeps repeated executions consistent (a release at the
    // end with no acquire, or an acquire with no release, is an error on the next execution).
    const ImportState& initial = state_.resource(first.resource).initialState;
    TrackedState s;
    s.discardsOnEntry = first.writes() && !first.reads();
    s.queue = s.discardsOnEntry ? queue_ : state_.options.queueOfClass[static_cast<size_t>(initial.queue)];
    s.layout = s.discardsOnEntry ? Layout::Undefined : initial.layout;
    // What happened before the graph is treated as a write: later uses wait for it.
    s.writeStages = initial.stages;
    s.writeAccess = initial.access;
    return s;
  }

  // A transient starts UNDEFINED on its first user's queue. The earlier occupants of its memory on
  // that queue (see TransientPlacer) stand for its last write: its first barrier waits for them and
  // makes their writes available.
  [[nodiscard]] TrackedState enterTransient(uint32_t resource) const {
    const Placement& placement = state_.out.aliasing.placements[resource];
    TrackedState s;
    s.queue = queue_;
    s.writeStages = placement.aliasedAfterStages;
    s.writeAccess = placement.aliasedAfterWrites;
    return s;
  }

  void transferOwnership(uint32_t resource, const TrackedState& s, const Use& use, Layout layout) {
    // An imported resource owned by another family before the graph was released by its owner;
    // only the acquire is ours then.
    if (s.lastStep != kInvalidIndex) {
      addAfter(s.lastStep, barrier(Barrier::Kind::Release, resource,
                                   {s.writeStages | s.readStages, s.writeAccess, s.layout, s.queue},
                                   {kStageNone, kAccessNone, layout, queue_}));
    }
    addBefore(barrier(Barrier::Kind::Acquire, resource, {kStageNone, kAccessNone, s.layout, s.queue},
                      {use.stages, use.accessMask, layout, queue_}));
  }

  void sameQueueHazard(uint32_t resource, bool texture, const TrackedState& s, const Use& use, Layout layout) {
    const bool layoutChange = texture && layout != s.layout;
    StageMask srcStages = s.writeStages;
    if (use.writes() || layoutChange) {
      // WAW/RAW(+write) wait for the last write, WAR for every read since it.
      srcStages |= s.readStages;
      if (srcStages == kStageNone && !layoutChange) return;
    } else {
      // Read after write: needed unless an earlier barrier already made the write visible here.
      const bool visible = (use.stages & ~s.visibleStages) == 0 && (use.accessMask & ~s.visibleAccess) == 0;
      if (s.writeStages == kStageNone || visible) return;
    }
    addBefore(barrier(Barrier::Kind::Transition, resource,
                      {srcStages, s.writeAccess, texture ? s.layout : Layout::Undefined, queue_},
                      {use.stages, use.accessMask, texture ? layout : Layout::Undefined, queue_}));
  }

  // A shared buffer last used on another queue: the semaphore wait that orders the two uses (every
  // cross-queue hazard is an edge, and waits cover all commands) already made the earlier writes
  // visible to everything after it on this queue. A barrier here would be redundant, and could not
  // even name the other queue's stages where the families differ (a transfer-only queue cannot
  // wait for a compute stage). Nothing is left to wait for on this queue.
  static void handOverSharedBuffer(TrackedState& s) {
    s.writeStages = kStageNone;
    s.writeAccess = kAccessNone;
    s.readStages = kStageNone;
  }

  void advance(TrackedState& s, const Use& use, Layout layout, bool transitioned) const {
    if (!use.writes() && transitioned) {
      // The barrier just placed (layout transition / acquire) made the last write available and is
      // itself a write, ordered only before this use's stages. Later barriers must chain through
      // those stages (srcStages = them, srcAccess = none: nothing left to make available), not
      // name the original writer's stages, which would not chain (e.g. colour output -> compute).
      s.writeStages = use.stages;
      s.writeAccess = kAccessNone;
      s.readStages = use.stages;
      s.visibleStages = use.stages;
      s.visibleAccess = use.accessMask;
    } else if (use.writes()) {
      s.writeStages = use.stages;
      s.writeAccess = use.accessMask & kWriteAccesses;
      s.readStages = kStageNone;
      s.visibleStages = kStageNone;
      s.visibleAccess = kAccessNone;
    } else {
      // Every read either got a barrier from the write or found the write already visible.
      s.readStages |= use.stages;
      s.visibleStages |= use.stages;
      s.visibleAccess |= use.accessMask;
    }
    s.queue = queue_;
    s.layout = layout;
    s.lastStep = step_;
  }

  CompileState& state_;
  std::vector<TrackedState> states_;  // per resource
  uint32_t queue_ = 0;                // queue and step of the node whose uses are being planned
  uint32_t step_ = 0;
  uint32_t firstBefore_ = 0;                 // where the walked node's barriers before it begin
  std::vector<std::vector<Barrier>> after_;  // per step: the barriers after it, in the order found
};

// A node's uses, one per resource. A node that uses a resource twice (e.g. read + resolve) is
// planned as one combined use: its versions say whether any of the uses read or wrote, its stages
// and access mask cover both, and its layout is theirs if they agree, else General. (Its `access`
// and `shaderStages` are the first use's; the planner does not read them.)
std::vector<Use> mergedUses(std::span<const Use> uses) {
  std::vector<Use> merged;
  for (const Use& use : uses) {
    const auto same =
        std::find_if(merged.begin(), merged.end(), [&](const Use& m) { return m.resource == use.resource; });
    if (same == merged.end()) {
      merged.push_back(use);
      continue;
    }
    same->stages |= use.stages;
    same->accessMask |= use.accessMask;
    if (!same->reads()) same->readVersion = use.readVersion;
    if (!same->writes()) same->writeVersion = use.writeVersion;
    if (same->layout != use.layout) same->layout = Layout::General;
  }
  return merged;
}

// What the walk keeps about a resource for lifetimes and placement.
struct ResourceWalk {
  uint32_t usesLeft = 0;          // alive uses not walked yet: 0 after the last user's
  QueueStages stagesOnQueue{};    // stages used on each queue
  QueueAccesses writesOnQueue{};  // writes made on each queue
  QueueArray lastSigmaOnQueue{};  // largest σ of a user on each queue
};

// One walk over the alive uses in execution order: lifetimes, placement (with or without aliasing)
// and barriers. A transient is placed at its first use and its range goes back to the free list
// after its last user (so users at one position never share memory); an imported resource goes
// back to its final state after its last user. A resource's last user is found by counting down its
// alive uses (counted while culling). The first walk of a compile also resolves each transient's
// memory requirements.
void walkUses(CompileState& state, bool alias, bool firstWalk) {
  std::vector<ResourceWalk> walk(state.resourceCount);
  for (uint32_t r = 0; r < state.resourceCount; ++r) walk[r].usesLeft = state.aliveUses[r];
  TransientPlacer placer(state, alias, firstWalk);
  BarrierPlanner barriers(state);
  state.out.lifetimes.assign(state.resourceCount, {});
  state.out.resourceAlive.assign(state.resourceCount, false);
  const auto& order = state.out.order;
  for (uint32_t position = 0; position < order.size(); ++position) {
    const uint32_t node = order[position];
    const uint32_t queue = state.queueOf[node];
    const uint32_t sigma = state.queueCount > 1 ? state.sigma[node] : 0;
    // Every use is counted off first, so that a combined use knows whether it was the last.
    for (const Use& use : state.uses(node)) --walk[use.resource].usesLeft;
    const std::vector<Use> uses = mergedUses(state.uses(node));
    barriers.beginNode(node);
    for (const Use& use : uses) {
      const uint32_t r = use.resource;
      ResourceWalk& w = walk[r];
      const bool first = !state.out.lifetimes[r].used();
      if (first) {
        state.out.lifetimes[r].first = position;
        state.out.resourceAlive[r] = true;
        if (!state.isImported(r)) placer.place(r, node);
      }
      w.stagesOnQueue[queue] |= use.stages;
      w.writesOnQueue[queue] |= use.accessMask & kWriteAccesses;
      w.lastSigmaOnQueue[queue] = sigma;  // uses come in order, and σ grows with it on a queue
      barriers.planUse(use, first);
    }
    barriers.endNode();
    // After the node: transients give their memory back, imports go to their final state.
    for (const Use& use : uses) {
      const uint32_t r = use.resource;
      if (walk[r].usesLeft != 0) continue;
      state.out.lifetimes[r].last = position;
      if (state.isImported(r)) {
        barriers.finalState(r);
      } else {
        placer.release(r, walk[r].lastSigmaOnQueue, walk[r].stagesOnQueue, walk[r].writesOnQueue);
      }
    }
  }
  barriers.emitAfterBarriers();
}

}  // namespace

void placeAndPlanBarriers(CompileState& state) {
  walkUses(state, state.options.alias, true);
  // Fragmentation (mixed alignments, ranges that cannot merge) can make a placement worse than
  // none; then keep whichever of the two layouts is smaller (barriers follow the placement).
  AliasingPlan& plan = state.out.aliasing;
  if (plan.peakBytesAliased <= plan.peakBytesUnaliased) return;
  AliasingPlan aliased = std::move(plan);
  std::vector<Barrier> aliasedBarriers = std::move(state.out.barriers);
  const std::vector<Step> aliasedSteps = state.out.steps;
  walkUses(state, false, false);
  if (plan.peakBytesAliased > aliased.peakBytesAliased) {
    plan = std::move(aliased);
    state.out.barriers = std::move(aliasedBarriers);
    state.out.steps = aliasedSteps;
  }
}

}  // namespace fgb::graph::detail
