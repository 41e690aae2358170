// Barrier invariants, checked by replaying each queue's timeline (barriers before a step, the
// step's uses, barriers after it) per resource:
//  - every same-queue hazard (RAW, WAR, WAW, or a layout change) between two uses is covered by
//    barriers between them: an execution dependency (directly or by chaining) and, after a write,
//    availability + visibility for the later access; unless a use on another queue sits between
//    them in semaphore order (semaphores are full memory dependencies);
//  - every texture use finds the resource in its layout; old layouts match what came before, and
//    UNDEFINED (discard) only precedes uses that do not read; transients start from UNDEFINED;
//  - reads of data produced on another queue family are preceded by an acquire, releases and
//    acquires pair up, and the release happens before the acquire;
//  - imported textures end in their final layout.
#include <fgb/graph/barrier_names.hpp>
#include "invariants.hpp"

#include <algorithm>
#include <tuple>

namespace fgb::graph::test {
namespace {

struct Event {
  uint32_t barrier = kInvalidIndex;  // a barrier, or
  uint32_t use = kInvalidIndex;      // an index into GraphModel::uses
};

struct Replay {
  const GraphModel& model;
  const FrameGraph& graph;
  const CompiledGraph& compiled;
  const CompileOptions& options;
  std::vector<std::vector<Event>> timeline;  // per queue
  std::vector<std::pair<uint32_t, uint32_t>> useAt;  // use -> (queue, position in timeline)
  std::vector<uint32_t> barrierNode;                  // barrier -> node of the step recording it
  Problems problems;
};

StageMask expand(StageMask stages) { return (stages & kStageAllCommands) != 0 ? ~0u : stages; }
bool covers(StageMask scope, StageMask stages) { return (stages & ~expand(scope)) == 0; }

AccessInfo infoOf(const Replay& r, uint32_t use) {
  const ModelUse& u = r.model.uses[use];
  return accessInfo(u.access, r.model.nodeType[u.node], u.shaderStages);
}

bool isTexture(const Replay& r, uint32_t resource) { return r.model.kind[resource] == ResourceKind::Texture; }

void appendRange(Replay& r, uint32_t step, uint32_t queue, BarrierRange range, Barrier::Kind allowed, bool before) {
  if (range.first + range.count > r.compiled.barriers.size()) {
    r.problems.push_back("barrier range out of bounds");
    return;
  }
  for (uint32_t b = range.first; b < range.first + range.count; ++b) {
    const Barrier& barrier = r.compiled.barriers[b];
    const bool kindOk = barrier.kind == Barrier::Kind::Transition || barrier.kind == allowed;
    const uint32_t ownQueue = barrier.kind == Barrier::Kind::Release ? barrier.srcQueue : barrier.dstQueue;
    const bool queuesOk = barrier.kind == Barrier::Kind::Transition
                              ? barrier.srcQueue == queue && barrier.dstQueue == queue
                              : ownQueue == queue && barrier.srcQueue != barrier.dstQueue;
    if (!kindOk || !queuesOk || barrier.resource >= r.model.resourceCount()) {
      r.problems.push_back(std::string(before ? "before" : "after") + "-range barrier " + std::to_string(b) +
                           " has the wrong kind, queues or resource");
      continue;
    }
    r.timeline[queue].push_back({.barrier = b});
    r.barrierNode[b] = r.compiled.steps[step].node;
  }
}

void buildTimelines(Replay& r) {
  r.timeline.assign(r.compiled.queueCount, {});
  r.useAt.assign(r.model.uses.size(), {kInvalidIndex, kInvalidIndex});
  std::vector<std::vector<uint32_t>> usesOfNode(r.model.nodeCount());
  for (uint32_t u = 0; u < r.model.uses.size(); ++u) usesOfNode[r.model.uses[u].node].push_back(u);
  r.barrierNode.assign(r.compiled.barriers.size(), kInvalidIndex);
  for (uint32_t s = 0; s < r.compiled.steps.size(); ++s) {
    const Step& step = r.compiled.steps[s];
    const uint32_t queue = r.compiled.nodes[step.node].queue;
    appendRange(r, s, queue, step.before, Barrier::Kind::Acquire, true);
    for (uint32_t u : usesOfNode[step.node]) {
      r.useAt[u] = {queue, static_cast<uint32_t>(r.timeline[queue].size())};
      r.timeline[queue].push_back({.use = u});
    }
    appendRange(r, s, queue, step.after, Barrier::Kind::Release, false);
  }
}

// Chain walk over the barriers on `resource` strictly between positions `from` and `to`.
bool hazardCovered(const Replay& r, uint32_t queue, uint32_t from, uint32_t to, const AccessInfo& a,
                   const AccessInfo& b, uint32_t resource) {
  StageMask reached = 0;
  StageMask visibleStages = 0;
  AccessMask visibleAccess = 0;
  const AccessMask aWrites = a.access & kWriteAccesses;
  bool available = aWrites == 0;
  for (uint32_t p = from + 1; p < to; ++p) {
    const Event& e = r.timeline[queue][p];
    if (e.barrier == kInvalidIndex || r.compiled.barriers[e.barrier].resource != resource) continue;
    const Barrier& barrier = r.compiled.barriers[e.barrier];
    const bool direct = covers(barrier.srcStages, a.stages);
    if (!direct && (reached & expand(barrier.srcStages)) == 0) continue;
    reached |= expand(barrier.dstStages);
    if (direct && (aWrites & ~barrier.srcAccess) == 0) available = true;
    if (available) {
      visibleStages |= expand(barrier.dstStages);
      visibleAccess |= barrier.dstAccess;
    }
  }
  if (!covers(reached, b.stages)) return false;
  return aWrites == 0 || (available && covers(visibleStages, b.stages) && (b.access & ~visibleAccess) == 0);
}

bool orderedThroughOtherQueue(const Replay& r, const HappensBefore& hb, uint32_t a, uint32_t b) {
  const ModelUse& ua = r.model.uses[a];
  for (uint32_t c = 0; c < r.model.uses.size(); ++c) {
    const ModelUse& uc = r.model.uses[c];
    if (uc.resource != ua.resource || r.useAt[c].first == kInvalidIndex || r.useAt[c].first == r.useAt[a].first) continue;
    if (hb.ordered(ua.node, uc.node) && hb.ordered(uc.node, r.model.uses[b].node)) return true;
  }
  return false;
}

void checkSameQueueHazards(Replay& r, const HappensBefore& hb) {
  for (uint32_t a = 0; a < r.model.uses.size(); ++a) {
    for (uint32_t b = 0; b < r.model.uses.size(); ++b) {
      const ModelUse& ua = r.model.uses[a];
      const ModelUse& ub = r.model.uses[b];
      if (ua.resource != ub.resource || ua.node == ub.node || r.useAt[a].first == kInvalidIndex ||
          r.useAt[a].first != r.useAt[b].first || r.useAt[a].second >= r.useAt[b].second) {
        continue;
      }
      const AccessInfo ia = infoOf(r, a);
      const AccessInfo ib = infoOf(r, b);
      const bool layoutChange = isTexture(r, ua.resource) && ia.layout != ib.layout;
      if (!ia.writes && !ib.writes && !layoutChange) continue;
      if (orderedThroughOtherQueue(r, hb, a, b)) continue;
      if (!hazardCovered(r, r.useAt[a].first, r.useAt[a].second, r.useAt[b].second, ia, ib, ua.resource)) {
        r.problems.push_back("hazard on '" + r.model.resourceName[ua.resource] + "' between '" +
                             r.model.nodeName[ua.node] + "' (" + std::string(toString(ua.access)) + ") and '" +
                             r.model.nodeName[ub.node] + "' (" + std::string(toString(ub.access)) +
                             ") has no covering barrier");
      }
    }
  }
}

// Layout replay of one texture on one queue.
void checkLayoutsOn(Replay& r, uint32_t queue, uint32_t texture) {
  const ResourceDecl& decl = r.graph.resources()[texture];
  bool known = false;
  bool discarded = false;
  Layout current = Layout::Undefined;
  const std::string what = "texture '" + std::string(decl.name) + "' on queue " + std::to_string(queue);
  for (const Event& e : r.timeline[queue]) {
    if (e.barrier != kInvalidIndex) {
      const Barrier& b = r.compiled.barriers[e.barrier];
      if (b.resource != texture) continue;
      // An acquire's old layout is the releasing queue's; the release/acquire pairing checks it.
      if (known && b.kind != Barrier::Kind::Acquire && b.oldLayout != Layout::Undefined && b.oldLayout != current) {
        r.problems.push_back(what + ": barrier oldLayout " + std::string(layoutName(b.oldLayout)) + " but it is in " +
                             std::string(layoutName(current)));
      }
      discarded = b.oldLayout == Layout::Undefined;
      current = b.newLayout;
      known = true;
      continue;
    }
    const ModelUse& use = r.model.uses[e.use];
    if (use.resource != texture) continue;
    const Layout wanted = infoOf(r, e.use).layout;
    if (discarded && use.reads() && !(decl.imported && use.readPos == 0)) {
      r.problems.push_back(what + ": contents discarded (from UNDEFINED) right before '" +
                           r.model.nodeName[use.node] + "' reads them");
    }
    discarded = false;
    if (!known && !(decl.imported && decl.initialState.layout == wanted)) {
      r.problems.push_back(what + ": '" + r.model.nodeName[use.node] + "' uses it with no transition to " +
                           std::string(layoutName(wanted)));
    } else if (known && current != wanted) {
      r.problems.push_back(what + ": '" + r.model.nodeName[use.node] + "' needs " + std::string(layoutName(wanted)) +
                           " but it is in " + std::string(layoutName(current)));
    }
    current = wanted;
    known = true;
  }
}

uint32_t userWithOrder(const Replay& r, uint32_t resource, bool last) {
  uint32_t best = kInvalidIndex;
  for (uint32_t u = 0; u < r.model.uses.size(); ++u) {
    if (r.model.uses[u].resource != resource || r.useAt[u].first == kInvalidIndex) continue;
    const uint32_t order = r.compiled.nodes[r.model.uses[u].node].orderIndex;
    if (best == kInvalidIndex) best = u;
    const uint32_t bestOrder = r.compiled.nodes[r.model.uses[best].node].orderIndex;
    if (last ? order > bestOrder : order < bestOrder) best = u;
  }
  return best;
}

// Transients start from UNDEFINED; imported textures end in their final layout.
void checkFirstAndFinal(Replay& r, uint32_t texture) {
  const ResourceDecl& decl = r.graph.resources()[texture];
  const uint32_t first = userWithOrder(r, texture, false);
  const uint32_t last = userWithOrder(r, texture, true);
  if (first == kInvalidIndex) return;
  if (!decl.imported) {
    const auto [queue, position] = r.useAt[first];
    for (uint32_t p = 0; p < position; ++p) {
      const Event& e = r.timeline[queue][p];
      if (e.barrier != kInvalidIndex && r.compiled.barriers[e.barrier].resource == texture) {
        if (r.compiled.barriers[e.barrier].oldLayout != Layout::Undefined) {
          r.problems.push_back("transient '" + std::string(decl.name) + "': first transition not from UNDEFINED");
        }
        break;
      }
    }
    return;
  }
  const auto [queue, position] = r.useAt[last];
  Layout endLayout = infoOf(r, last).layout;
  for (uint32_t p = position + 1; p < r.timeline[queue].size(); ++p) {
    const Event& e = r.timeline[queue][p];
    if (e.barrier != kInvalidIndex && r.compiled.barriers[e.barrier].resource == texture) {
      endLayout = r.compiled.barriers[e.barrier].newLayout;
    }
  }
  if (endLayout != decl.finalState.layout) {
    r.problems.push_back("imported '" + std::string(decl.name) + "' ends in " + std::string(layoutName(endLayout)) +
                         ", not " + std::string(layoutName(decl.finalState.layout)));
  }
}

uint32_t familyOf(const Replay& r, uint32_t queue) { return r.options.familyOfQueue[queue]; }

// A read of data written on another queue family needs an acquire on the reader's queue since the
// last use there of another version.
void checkAcquireBeforeRead(Replay& r, uint32_t u, const std::vector<uint32_t>& producerQueue) {
  const ModelUse& use = r.model.uses[u];
  if (!use.reads() || use.readPos == 0 || r.useAt[u].first == kInvalidIndex) return;
  const auto [queue, position] = r.useAt[u];
  if (familyOf(r, producerQueue[static_cast<size_t>(use.readPos)]) == familyOf(r, queue)) return;
  const bool texture = r.graph.resources()[use.resource].kind == ResourceKind::Texture;
  if (!texture && r.options.buffersShareFamilies) return;  // shared buffers have no owner to change
  for (uint32_t p = position; p-- > 0;) {
    const Event& e = r.timeline[queue][p];
    if (e.barrier != kInvalidIndex) {
      const Barrier& b = r.compiled.barriers[e.barrier];
      if (b.resource == use.resource && b.kind == Barrier::Kind::Acquire) return;
      continue;
    }
    const ModelUse& other = r.model.uses[e.use];
    if (other.resource == use.resource && (other.writes() || other.readPos != use.readPos)) break;
  }
  r.problems.push_back("'" + r.model.nodeName[use.node] + "' reads '" + r.model.resourceName[use.resource] +
                       "' from another queue family without an acquire");
}

void checkOwnership(Replay& r, const HappensBefore& hb) {
  for (uint32_t resource = 0; resource < r.model.resourceCount(); ++resource) {
    std::vector<uint32_t> producerQueue;  // by chain position
    for (const ModelUse& use : r.model.uses) {
      if (use.resource != resource || !use.writes()) continue;
      if (producerQueue.size() <= static_cast<size_t>(use.writePos)) producerQueue.resize(use.writePos + 1, 0);
      producerQueue[static_cast<size_t>(use.writePos)] = r.compiled.nodes[use.node].queue;
    }
    for (uint32_t u = 0; u < r.model.uses.size(); ++u) {
      if (r.model.uses[u].resource == resource) checkAcquireBeforeRead(r, u, producerQueue);
    }
  }
  auto key = [](const Barrier& b) { return std::tuple(b.resource, b.srcQueue, b.dstQueue, b.oldLayout, b.newLayout); };
  for (uint32_t a = 0; a < r.compiled.barriers.size(); ++a) {
    const Barrier& acquire = r.compiled.barriers[a];
    if (acquire.kind != Barrier::Kind::Acquire || r.barrierNode[a] == kInvalidIndex) continue;
    bool paired = false;
    for (uint32_t rel = 0; rel < r.compiled.barriers.size() && !paired; ++rel) {
      const Barrier& release = r.compiled.barriers[rel];
      paired = release.kind == Barrier::Kind::Release && key(release) == key(acquire) &&
               r.barrierNode[rel] != kInvalidIndex && hb.ordered(r.barrierNode[rel], r.barrierNode[a]);
    }
    // The graph cannot record the release of an imported resource's first hand-off: its owner
    // before the graph did that. Only the acquire before the first use is ours.
    const uint32_t acquiring = r.barrierNode[a];
    const bool importedFirstUse = r.graph.resources()[acquire.resource].imported &&
                                  userWithOrder(r, acquire.resource, false) != kInvalidIndex &&
                                  r.model.uses[userWithOrder(r, acquire.resource, false)].node == acquiring;
    if (!paired && !importedFirstUse) {
      r.problems.push_back("acquire of '" + r.model.resourceName[acquire.resource] +
                           "' has no matching release ordered before it");
    }
  }
}

}  // namespace

Problems checkBarriers(const GraphModel& model, const FrameGraph& graph, const Reference& /*ref*/,
                       const CompiledGraph& compiled, const CompileOptions& options) {
  Replay replay{model, graph, compiled, options, {}, {}, {}, {}};
  buildTimelines(replay);
  if (!replay.problems.empty()) return replay.problems;
  const HappensBefore hb(compiled);
  checkSameQueueHazards(replay, hb);
  for (uint32_t resource = 0; resource < model.resourceCount(); ++resource) {
    if (!compiled.resourceAlive[resource] || !isTexture(replay, resource)) continue;
    for (uint32_t queue = 0; queue < compiled.queueCount; ++queue) checkLayoutsOn(replay, queue, resource);
    checkFirstAndFinal(replay, resource);
  }
  checkOwnership(replay, hb);
  return replay.problems;
}

}  // namespace fgb::graph::test
