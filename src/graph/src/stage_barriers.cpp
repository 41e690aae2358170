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
#include "transient_placer.hpp"

#include <span>

namespace fgb::graph::detail {
namespace {

// What the planner asks of a use. Uses are planned straight from the graph's Use records: a
// planner-specific copy of each, written field by field on the stack and read back at once, cost
// about 5 % of a compile in store-forwarding stalls. A node that uses a resource twice (e.g. read
// + resolve) is planned as one combined Use (see mergeUses): its versions say whether any of the
// uses read or wrote, its stages, access mask and layout cover both (its `access` and
// `shaderStages` are the first use's, and the planner does not read them).
bool reads(const Use& use) { return use.readVersion != kInvalidIndex; }
bool writes(const Use& use) { return use.writeVersion != kInvalidIndex; }

// Set at the resource's first use (startTransient for a transient, enterImport for an import) and
// only read after.
struct TrackedState {
  bool discardsOnEntry;  // imported, but first overwritten without being read (see below)
  Layout layout;
  uint8_t queue;
  StageMask writeStages;
  AccessMask writeAccess;
  StageMask readStages;     // reads since the last write
  StageMask visibleStages;  // the last write was made visible to these stages...
  AccessMask visibleAccess;  // ...and accesses
  uint32_t lastStep;
};
static_assert(kQueueClassCount <= 256, "TrackedState::queue is a byte");

// Everything the walk keeps about one resource, in one cache line: a use touches one line rather
// than one per array (which cost more than the work done with them). Constructing it does nothing:
// walkUses() sets what must start set, the rest is set at the resource's first use.
struct alignas(64) ResourceWalk {
  // NOLINTNEXTLINE(modernize-use-equals-default,cppcoreguidelines-pro-type-member-init): unset on purpose
  ResourceWalk() {}
  TrackedState tracked;
  std::array<StageMask, kQueueClassCount> stagesOnQueue;  // stages used on each queue
  QueueArray lastSigmaOnQueue;                            // largest σ of a user on each queue
  uint32_t usesLeft;  // alive uses not walked yet: 0 after the last user's
  uint32_t lastSeen;  // the last node seen using it (to find a node that uses it twice)
  bool started;       // its first user was walked
};

// Tracks the state of each resource through its uses, in execution order, and records the
// barriers each use needs. A step's ranges need only be contiguous, not in step order: barriers
// before a node are all found while its uses are walked, so they go straight to the output, each
// step's run where the walk reached it. Barriers after a node (ownership releases, found at a later
// node's use; final states of imports) are kept apart and appended grouped by step at the end.
class BarrierPlanner {
 public:
  BarrierPlanner(CompileState& state, ResourceWalk* walk)
      : state_(state), walk_(walk), traits_(state.resourceTraits.data()),
        familyOfQueue_(state.options.familyOfQueue), buffersShared_(state.options.buffersShareFamilies) {
    // Most uses get one barrier (transfers two): size it once, not by doubling.
    const size_t uses = state.graph.allUses().size();
    before_.clear();
    before_.reserve(uses + uses / 4);
  }

  // The uses that follow are the node's; endNode() closes its range of barriers before it.
  void beginNode(uint32_t node) {
    queue_ = state_.queueOf[node];
    step_ = state_.out.nodes[node].step;
    firstBefore_ = static_cast<uint32_t>(before_.size());
  }
  void endNode() {
    state_.out.steps[step_].before = {firstBefore_, static_cast<uint32_t>(before_.size()) - firstBefore_};
  }

  // Kept out of line: inlined, it made the walk's per-use code a call of its own instead, and the
  // walk about 3 % slower (the compiler's choice flips with small changes in this function's size).
  [[gnu::noinline]] void planUse(const Use& use, bool firstUse) {
    const uint32_t resource = use.resource;
    const bool texture = isTexture(resource);
    TrackedState& s = walk_[resource].tracked;
    if (firstUse && !isImported(resource)) {
      startTransient(s, use, texture);
      return;
    }
    if (firstUse) enterImport(s, use);
    const uint32_t queue = queue_;
    const uint32_t step = step_;
    const Layout layout = texture ? use.layout : Layout::Undefined;
    // An ownership transfer or a layout change is a write in disguise (see advance()).
    const bool ownerChanges = changesOwner(s.queue, queue, texture);
    const bool transitioned = ownerChanges || (texture && layout != s.layout);
    if (ownerChanges) {
      transferOwnership(resource, s, use, queue, layout);
    } else if (handsOverSharedBuffer(s.queue, queue, texture)) {
      handOverSharedBuffer(s);
    } else {
      sameQueueHazard(resource, texture, s, use, queue, layout);
    }
    advance(s, use, queue, step, layout, transitioned);
  }

  // After an imported resource's last use: back to the state the declaration asked for.
  void finalState(uint32_t resource) { finalState(resource, isTexture(resource), walk_[resource].tracked); }

 private:
  [[nodiscard]] uint32_t familyOf(uint32_t queue) const { return familyOfQueue_[queue]; }
  // Whether moving a resource between these queues is a queue-family ownership transfer. Buffers
  // shared by every family (CompileOptions::buffersShareFamilies) never need one.
  [[nodiscard]] bool changesOwner(uint32_t from, uint32_t to, bool texture) const {
    return (texture || !buffersShared_) && familyOf(from) != familyOf(to);
  }
  // Whether moving a resource between these queues hands a shared buffer over (see
  // handOverSharedBuffer): a semaphore orders and makes visible what crosses, not a barrier.
  [[nodiscard]] bool handsOverSharedBuffer(uint32_t from, uint32_t to, bool texture) const {
    return !texture && buffersShared_ && from != to;
  }
  // CompileState's isImported/isTexture, through a pointer kept here: the planner's hottest loads.
  [[nodiscard]] bool isImported(uint32_t resource) const { return (traits_[resource] & kResourceImported) != 0; }
  [[nodiscard]] bool isTexture(uint32_t resource) const { return (traits_[resource] & kResourceTexture) != 0; }

  // Appends a barrier before the node being walked, or after step `step`, and returns it to be
  // filled in. Barriers (and tracked states) are built in place: copying a struct just written
  // field by field on the stack stalls on store forwarding, which cost more than all the rest of
  // this planner.
  Barrier& addBefore(Barrier::Kind kind, uint32_t resource) {
    Barrier& b = before_.emplace_back();
    b.kind = kind;
    b.resource = resource;
    return b;
  }
  Barrier& addAfter(uint32_t step, Barrier::Kind kind, uint32_t resource) {
    afterInStepOrder_ &= lastAfterStep_ <= step;
    lastAfterStep_ = step;
    afterStep_.push_back(step);
    Barrier& b = after_.emplace_back();
    b.kind = kind;
    b.resource = resource;
    return b;
  }

  // An imported resource's state as the graph finds it, set at its first use, which is then planned
  // like any later one. (Transients start in startTransient.)
  void enterImport(TrackedState& s, const Use& first) const {
    s.readStages = kStageNone;
    s.visibleStages = kStageNone;
    s.visibleAccess = kAccessNone;
    s.lastStep = kInvalidIndex;
    // An imported resource whose first use in the graph overwrites it without reading needs no
    // ownership transfer in or out: Vulkan only asks for one when contents must survive the change
    // of queue family. Skipping both halves keeps repeated executions consistent (a release at the
    // end with no acquire, or an acquire with no release, is an error on the next execution).
    const ResourceDecl& decl = state_.graph.resources()[first.resource];
    s.discardsOnEntry = writes(first) && !reads(first);
    const uint32_t declaredQueue = state_.options.queueOfClass[static_cast<size_t>(decl.initialState.queue)];
    s.queue = static_cast<uint8_t>(s.discardsOnEntry ? queue_ : declaredQueue);
    s.layout = s.discardsOnEntry ? Layout::Undefined : decl.initialState.layout;
    // What happened before the graph is treated as a write: later uses wait for it.
    s.writeStages = decl.initialState.stages;
    s.writeAccess = decl.initialState.access;
  }

  // A transient's first use: the barrier from UNDEFINED, and the state after it, set from the use
  // alone. (Storing a "nothing yet" state and planning the use through the general path would read
  // that state back at once, which stalls on store forwarding.) The first use writes (nobody wrote
  // the first version); a read would be planned right all the same.
  void startTransient(TrackedState& s, const Use& use, bool texture) {
    firstUseBarrier(use.resource, texture, use, queue_);
    const bool write = writes(use);
    const StageMask readStages = write ? kStageNone : use.stages;
    s.discardsOnEntry = false;
    s.layout = texture ? use.layout : Layout::Undefined;
    s.queue = static_cast<uint8_t>(queue_);
    s.writeStages = write ? use.stages : kStageNone;
    s.writeAccess = write ? use.accessMask & kWriteAccesses : kAccessNone;
    s.readStages = readStages;
    s.visibleStages = readStages;
    s.visibleAccess = write ? kAccessNone : use.accessMask;
    s.lastStep = step_;
  }

  void firstUseBarrier(uint32_t resource, bool texture, const Use& use, uint32_t queue) {
    const StageMask aliased = state_.out.aliasing.placements.empty()
                                  ? kStageNone
                                  : state_.out.aliasing.placements[resource].aliasedAfterStages;
    if (!texture && aliased == kStageNone) return;  // a fresh buffer needs no barrier
    Barrier& b = addBefore(Barrier::Kind::Transition, resource);
    b.srcStages = aliased;
    b.dstStages = use.stages;
    b.dstAccess = use.accessMask;
    b.oldLayout = Layout::Undefined;
    b.newLayout = texture ? use.layout : Layout::Undefined;
    b.srcQueue = b.dstQueue = queue;
  }

  void transferOwnership(uint32_t resource, const TrackedState& s, const Use& use, uint32_t queue,
                         Layout layout) {
    // An imported resource owned by another family before the graph was released by its owner;
    // only the acquire is ours then.
    if (s.lastStep != kInvalidIndex) {
      Barrier& release = addAfter(s.lastStep, Barrier::Kind::Release, resource);
      release.srcStages = s.writeStages | s.readStages;
      release.srcAccess = s.writeAccess;
      release.oldLayout = s.layout;
      release.newLayout = layout;
      release.srcQueue = s.queue;
      release.dstQueue = queue;
    }
    Barrier& acquire = addBefore(Barrier::Kind::Acquire, resource);
    acquire.dstStages = use.stages;
    acquire.dstAccess = use.accessMask;
    acquire.oldLayout = s.layout;
    acquire.newLayout = layout;
    acquire.srcQueue = s.queue;
    acquire.dstQueue = queue;
  }

  void sameQueueHazard(uint32_t resource, bool texture, const TrackedState& s, const Use& use,
                       uint32_t queue, Layout layout) {
    const bool layoutChange = texture && layout != s.layout;
    StageMask srcStages = s.writeStages;
    if (writes(use) || layoutChange) {
      // WAW/RAW(+write) wait for the last write, WAR for every read since it.
      srcStages |= s.readStages;
      if (srcStages == kStageNone && !layoutChange) return;
    } else {
      // Read after write: needed unless an earlier barrier already made the write visible here.
      const bool visible = (use.stages & ~s.visibleStages) == 0 && (use.accessMask & ~s.visibleAccess) == 0;
      if (s.writeStages == kStageNone || visible) return;
    }
    Barrier& b = addBefore(Barrier::Kind::Transition, resource);
    b.srcStages = srcStages;
    b.srcAccess = s.writeAccess;
    b.dstStages = use.stages;
    b.dstAccess = use.accessMask;
    b.oldLayout = texture ? s.layout : Layout::Undefined;
    b.newLayout = texture ? layout : Layout::Undefined;
    b.srcQueue = b.dstQueue = queue;
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

  static void advance(TrackedState& s, const Use& use, uint32_t queue, uint32_t step, Layout layout,
                      bool transitioned) {
    if (!writes(use) && transitioned) {
      // The barrier just placed (layout transition / acquire) made the last write available and is
      // itself a write, ordered only before this use's stages. Later barriers must chain through
      // those stages (srcStages = them, srcAccess = none: nothing left to make available), not
      // name the original writer's stages, which would not chain (e.g. colour output -> compute).
      s.writeStages = use.stages;
      s.writeAccess = kAccessNone;
      s.readStages = use.stages;
      s.visibleStages = use.stages;
      s.visibleAccess = use.accessMask;
    } else if (writes(use)) {
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
    s.queue = static_cast<uint8_t>(queue);
    s.layout = layout;
    s.lastStep = step;
  }

  void finalState(uint32_t resource, bool texture, const TrackedState& s) {
    const ResourceDecl& decl = state_.graph.resources()[resource];
    if (s.lastStep == kInvalidIndex) return;
    const ImportState& final = decl.finalState;
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
    Barrier& b = addAfter(s.lastStep, queueChange ? Barrier::Kind::Release : Barrier::Kind::Transition, resource);
    b.srcStages = s.writeStages | s.readStages;
    b.srcAccess = s.writeAccess;
    b.dstStages = dstStages;
    b.dstAccess = dstAccess;
    b.oldLayout = texture ? s.layout : Layout::Undefined;
    b.newLayout = texture ? finalLayout : Layout::Undefined;
    b.srcQueue = s.queue;
    b.dstQueue = handedOver ? s.queue : finalQueue;
  }

 public:
  // Appends the barriers after steps to the output, grouped by step (a stable counting sort,
  // unless they came in step order already), and sets each step's after-range.
  void emitAfterBarriers() {
    auto& steps = state_.out.steps;
    const auto base = static_cast<uint32_t>(before_.size());
    const auto stepCount = static_cast<uint32_t>(steps.size());
    if (after_.empty()) {
      for (Step& step : steps) step.after = {base, 0};
      return;
    }
    ScratchVector<uint32_t> stepStart(size_t{stepCount} + 1, 0);
    for (const uint32_t step : afterStep_) ++stepStart[step + 1];
    for (uint32_t i = 1; i <= stepCount; ++i) stepStart[i] += stepStart[i - 1];
    if (afterInStepOrder_) {
      before_.insert(before_.end(), after_.begin(), after_.end());
    } else {
      before_.resize(size_t{base} + after_.size());
      ScratchVector<uint32_t> cursor(stepStart.begin(), stepStart.end() - 1);
      for (uint32_t i = 0; i < after_.size(); ++i) before_[base + cursor[afterStep_[i]]++] = after_[i];
    }
    for (uint32_t s = 0; s < stepCount; ++s) steps[s].after = {base + stepStart[s], stepStart[s + 1] - stepStart[s]};
  }

 private:
  CompileState& state_;
  ResourceWalk* walk_;     // per resource
  const uint8_t* traits_;  // state_.resourceTraits
  const std::array<uint32_t, kQueueClassCount> familyOfQueue_;
  const bool buffersShared_;
  uint32_t queue_ = 0;  // queue and step of the node whose uses are being planned
  uint32_t step_ = 0;
  std::vector<Barrier>& before_ = state_.out.barriers;  // the output: barriers before steps, then after
  uint32_t firstBefore_ = 0;                    // where the walked node's barriers before it begin
  ScratchVector<Barrier> after_;                // barriers after steps, in the order found...
  ScratchVector<uint32_t> afterStep_;           // ...and the step each follows
  uint32_t lastAfterStep_ = 0;                  // the step of the last barrier after one
  bool afterInStepOrder_ = true;
};

// `uses`, one per resource, into `merged` (for a node that uses some resource more than once).
// `mergedAt[r]` is where r went, when merged[mergedAt[r]] says so: a sparse set, valid without
// clearing between nodes.
void mergeUses(std::span<const Use> uses, ScratchVector<Use>& merged, ScratchVector<uint32_t>& mergedAt) {
  merged.clear();
  for (const Use& use : uses) {
    const uint32_t at = mergedAt[use.resource];
    if (at >= merged.size() || merged[at].resource != use.resource) {
      mergedAt[use.resource] = static_cast<uint32_t>(merged.size());
      merged.push_back(use);
      continue;
    }
    Use& combined = merged[at];
    combined.stages |= use.stages;
    combined.accessMask |= use.accessMask;
    if (!reads(combined)) {
      combined.readVersion = use.readVersion;
      combined.readProducer = use.readProducer;
    }
    if (!writes(combined)) combined.writeVersion = use.writeVersion;
    if (combined.layout != use.layout) combined.layout = Layout::General;
  }
}

// Counts off each of a node's uses from its resource's uses left; returns whether the node uses
// some resource more than once.
bool countOffAndFindRepeats(std::span<const Use> uses, ResourceWalk* walk, uint32_t node) {
  bool repeats = false;
  for (const Use& use : uses) {
    ResourceWalk& w = walk[use.resource];
    repeats |= w.lastSeen == node;
    w.lastSeen = node;
    --w.usesLeft;
  }
  return repeats;
}

// One walk over the alive uses in execution order: lifetimes, placement (with or without aliasing)
// and barriers. A transient is placed at its first use and its range goes back to the free list
// after its last user (so users at one position never share memory); an imported resource goes
// back to its final state after its last user. A resource's last user is found by counting down its
// alive uses (counted while culling). The first walk of a compile also resolves each transient's
// memory requirements.
void walkUses(CompileState& state, bool alias, bool firstWalk) {
  const uint32_t resources = state.resourceCount;
  ScratchVector<ResourceWalk> walkStates;
  walkStates.resize(resources);  // constructs nothing (see ResourceWalk)
  ResourceWalk* const walk = walkStates.data();
  const bool mayRepeat = state.graph.someNodeUsesAResourceTwice();
  for (uint32_t r = 0; r < resources; ++r) {
    walk[r].usesLeft = state.aliveUses[r];
    walk[r].lastSeen = kInvalidIndex;
    walk[r].started = false;
  }
  TransientPlacer placer(state, alias, firstWalk);
  BarrierPlanner barriers(state, walk);
  // Outputs of the walk, written afresh by each (a fallback walk repeats the first one's).
  state.out.lifetimes.assign(resources, {});
  state.out.resourceAlive.assign(resources, false);
  Lifetime* const lifetimes = state.out.lifetimes.data();
  std::vector<bool>& resourceAlive = state.out.resourceAlive;
  const bool severalQueues = state.queueCount > 1;
  ScratchVector<Use> merged;
  ScratchVector<uint32_t> mergedAt;  // sized when first needed (see mergeUses)
  ScratchVector<uint32_t> ending;  // resources whose last user is the node being walked
  const auto& order = state.out.order;
  for (uint32_t position = 0; position < order.size(); ++position) {
    const uint32_t node = order[position];
    barriers.beginNode(node);
    const uint32_t queue = state.queueOf[node];
    const uint32_t sigma = severalQueues ? state.sync[node].sigma : 0;  // (with one queue: not used)
    const std::span<const Use> uses = state.graph.uses(node);
    if (ending.size() < uses.size()) ending.resize(uses.size());
    uint32_t endingCount = 0;
    auto visit = [&](const Use& use) {
      const uint32_t r = use.resource;
      ResourceWalk& w = walk[r];
      const bool first = !w.started;
      if (first) {
        w.started = true;
        // What placement needs about the users on each queue (see TransientPlacer).
        w.stagesOnQueue = {};
        w.lastSigmaOnQueue = {};
        lifetimes[r].first = position;
        resourceAlive[r] = true;
        if (!state.isImported(r)) placer.place(r, node);
      }
      w.stagesOnQueue[queue] |= use.stages;
      // Uses come in order, and σ grows with the order position on each queue.
      w.lastSigmaOnQueue[queue] = sigma;
      barriers.planUse(use, first);
      // Noted without a branch: whether a use is its resource's last is as good as random.
      ending[endingCount] = r;
      endingCount += w.usesLeft == 0 ? 1 : 0;
    };
    // One use per resource: a node that uses one twice (rare) has its uses combined first. Every
    // use of the node is counted off first, so that the combined one sees whether it was the last.
    // Graphs without such a node (most) skip looking for one.
    if (!mayRepeat) {
      for (const Use& use : uses) {
        --walk[use.resource].usesLeft;
        visit(use);
      }
    } else if (countOffAndFindRepeats(uses, walk, node)) {
      if (mergedAt.empty()) mergedAt.resize(resources);
      mergeUses(uses, merged, mergedAt);
      for (const Use& use : merged) visit(use);
    } else {
      for (const Use& use : uses) visit(use);
    }
    barriers.endNode();
    // After the node: transients give their memory back, imports go to their final state.
    for (uint32_t i = 0; i < endingCount; ++i) {
      const uint32_t r = ending[i];
      lifetimes[r].last = position;
      if (state.isImported(r)) {
        barriers.finalState(r);
      } else {
        placer.release(r, walk[r].lastSigmaOnQueue, walk[r].stagesOnQueue);
      }
    }
  }
  placer.finish();
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
  plan = {};
  state.out.barriers.clear();
  walkUses(state, false, false);
  if (plan.peakBytesAliased > aliased.peakBytesAliased) {
    plan = std::move(aliased);
    state.out.barriers = std::move(aliasedBarriers);
    state.out.steps = aliasedSteps;
  }
}

}  // namespace fgb::graph::detail
