// Structural invariants: declaration, culling, order and levels, queues and G*, submits.
#include "invariants.hpp"

#include <algorithm>
#include <set>
#include <sstream>

namespace fgb::graph::test {
namespace {

std::string edgeText(const GraphModel& model, uint32_t from, uint32_t to) {
  return "'" + model.nodeName[from] + "' -> '" + model.nodeName[to] + "'";
}

// Consecutive nodes of one queue in global order: the order a queue executes them in.
std::vector<Edge> sameQueueChain(const CompiledGraph& compiled) {
  std::vector<Edge> chain;
  std::vector<uint32_t> lastOnQueue(compiled.queueCount, kInvalidIndex);
  for (uint32_t node : compiled.order) {
    uint32_t& last = lastOnQueue[compiled.nodes[node].queue];
    if (last != kInvalidIndex) chain.push_back({last, node});
    last = node;
  }
  return chain;
}

// Two readers of one version on different queues, or of a texture in different layouts, may be
// chained: the hand-over (ownership transfer, layout change) is a write in disguise.
bool readersNeedingAChain(const GraphModel& model, const CompiledGraph& compiled, uint32_t a, uint32_t b) {
  for (const ModelUse& ua : model.uses) {
    for (const ModelUse& ub : model.uses) {
      if (ua.node != a || ub.node != b || ua.resource != ub.resource || !ua.reads() || !ub.reads() ||
          ua.readPos != ub.readPos) {
        continue;
      }
      const Layout la = accessInfo(ua.access, model.nodeType[a], ua.shaderStages).layout;
      const Layout lb = accessInfo(ub.access, model.nodeType[b], ub.shaderStages).layout;
      const bool texture = model.kind[ua.resource] == ResourceKind::Texture;
      if (compiled.nodes[a].queue != compiled.nodes[b].queue || (texture && la != lb)) return true;
    }
  }
  return false;
}

// Longest path from a source over `edges` (alive nodes), by relaxation.
std::vector<uint32_t> longestPaths(uint32_t nodeCount, const std::vector<Edge>& edges) {
  std::vector<uint32_t> level(nodeCount, 0);
  for (uint32_t round = 0; round < nodeCount; ++round) {
    bool changed = false;
    for (const Edge& e : edges) {
      if (level[e.to] < level[e.from] + 1) {
        level[e.to] = level[e.from] + 1;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return level;
}

bool sameUse(const ModelUse& a, const ModelUse& b) {
  return a.node == b.node && a.resource == b.resource && a.readPos == b.readPos && a.writePos == b.writePos &&
         a.access == b.access;
}

}  // namespace

HappensBefore::HappensBefore(const CompiledGraph& compiled) : compiled_(&compiled) {
  const auto count = static_cast<uint32_t>(compiled.submits.size());
  std::vector<uint32_t> firstOfQueue(compiled.queueCount, kInvalidIndex);
  for (uint32_t s = count; s-- > 0;) firstOfQueue[compiled.submits[s].queue] = s;
  std::vector<Edge> edges;
  for (uint32_t s = 0; s < count; ++s) {
    const Submit& submit = compiled.submits[s];
    if (s + 1 < count && compiled.submits[s + 1].queue == submit.queue) edges.push_back({s, s + 1});
    for (const SemaphoreWait& wait : submit.waits) {
      if (wait.queue >= compiled.queueCount || wait.value == 0) continue;
      const uint32_t first = firstOfQueue[wait.queue];
      if (first == kInvalidIndex || wait.value > compiled.submitsPerQueue[wait.queue]) continue;
      edges.push_back({first + static_cast<uint32_t>(wait.value) - 1, s});
    }
  }
  const Reachability reach(count, edges);
  submitReach_.assign(count, std::vector<char>(count, 0));
  for (uint32_t a = 0; a < count; ++a) {
    for (uint32_t b = 0; b < count; ++b) submitReach_[a][b] = reach.reaches(a, b) ? 1 : 0;
    if (reach.reaches(a, a)) acyclic_ = false;
  }
}

bool HappensBefore::ordered(uint32_t before, uint32_t after) const {
  const NodeInfo& a = compiled_->nodes[before];
  const NodeInfo& b = compiled_->nodes[after];
  if (a.queue == b.queue) return a.step < b.step;
  return submitReach_[a.submit][b.submit] != 0;
}

Problems checkDeclaration(const GraphModel& expected, const FrameGraph& graph) {
  Problems problems;
  const GraphModel recorded = modelFromGraph(graph);
  if (recorded.nodeName != expected.nodeName) problems.push_back("node names differ");
  if (recorded.sideEffect != expected.sideEffect) problems.push_back("side-effect flags differ");
  if (recorded.nodeClass != expected.nodeClass) problems.push_back("queue classes differ");
  if (recorded.imported != expected.imported) problems.push_back("imported flags differ");
  if (recorded.uses.size() != expected.uses.size()) {
    problems.push_back("use count " + std::to_string(recorded.uses.size()) + " != " +
                       std::to_string(expected.uses.size()));
    return problems;
  }
  for (size_t i = 0; i < expected.uses.size(); ++i) {
    if (!sameUse(recorded.uses[i], expected.uses[i])) {
      problems.push_back("use " + std::to_string(i) + " of '" + expected.nodeName[expected.uses[i].node] +
                         "' recorded differently (versions or access)");
    }
  }
  return problems;
}

Problems checkCulling(const GraphModel& model, const FrameGraph& graph, const Reference& ref,
                      const CompiledGraph& compiled) {
  Problems problems;
  for (uint32_t n = 0; n < model.nodeCount(); ++n) {
    const NodeInfo& info = compiled.nodes[n];
    if (info.culled == ref.alive[n]) {
      problems.push_back("'" + model.nodeName[n] + "' culled=" + std::to_string(info.culled) + ", expected " +
                         std::to_string(!ref.alive[n]));
      continue;
    }
    if (!info.culled) {
      if (info.reason != CullReason::Alive) problems.push_back("'" + model.nodeName[n] + "' alive with a reason");
      continue;
    }
    const bool writes = std::any_of(model.uses.begin(), model.uses.end(),
                                    [n](const ModelUse& u) { return u.node == n && u.writes(); });
    const CullReason expected = writes ? CullReason::OutputsUnread : CullReason::NoOutputs;
    if (info.reason != expected) problems.push_back("'" + model.nodeName[n] + "' culled for the wrong reason");
    const std::string why = cullDiagnostic(graph, compiled, n);
    if (why.empty()) problems.push_back("culled '" + model.nodeName[n] + "' has no diagnostic");
    for (const ModelUse& use : model.uses) {  // "writes X, nobody alive reads it" must name X
      const std::string written = "'" + model.resourceName[use.resource] + "'";
      if (use.node == n && use.writes() && why.find(written) == std::string::npos) {
        problems.push_back("diagnostic for culled '" + model.nodeName[n] + "' does not name what it writes: " + why);
      }
    }
  }
  return problems;
}

Problems checkOrderAndLevels(const GraphModel& model, const Reference& ref, const CompiledGraph& compiled) {
  Problems problems;
  std::vector<uint32_t> expectedOrderSet;
  for (uint32_t n = 0; n < model.nodeCount(); ++n) {
    if (ref.alive[n]) expectedOrderSet.push_back(n);
  }
  std::vector<uint32_t> sortedOrder = compiled.order;
  std::sort(sortedOrder.begin(), sortedOrder.end());
  if (sortedOrder != expectedOrderSet) return {"order does not hold exactly the alive nodes"};
  const std::vector<uint32_t> level = longestPaths(model.nodeCount(), compiled.edges);
  for (uint32_t i = 0; i < compiled.order.size(); ++i) {
    const uint32_t node = compiled.order[i];
    if (compiled.nodes[node].orderIndex != i) problems.push_back("orderIndex of '" + model.nodeName[node] + "'");
    if (compiled.nodes[node].level != level[node] || level[node] < ref.level[node]) {
      problems.push_back("level of '" + model.nodeName[node] + "' is " + std::to_string(compiled.nodes[node].level) +
                         ", longest path over the edges says " + std::to_string(level[node]));
    }
    if (i > 0 && compiled.nodes[compiled.order[i - 1]].level > compiled.nodes[node].level) {
      problems.push_back("levels decrease at order position " + std::to_string(i));
    }
  }
  for (const RequiredOrder& r : ref.required) {
    if (compiled.nodes[r.before].orderIndex >= compiled.nodes[r.after].orderIndex) {
      problems.push_back("order not topological: " + edgeText(model, r.before, r.after));
    }
  }
  for (const Edge& e : compiled.edges) {
    if (e.from < model.nodeCount() && e.to < model.nodeCount() &&
        compiled.nodes[e.from].orderIndex >= compiled.nodes[e.to].orderIndex) {
      problems.push_back("order not topological for edge " + edgeText(model, e.from, e.to));
    }
  }
  // Edges: alive, no self-loops or duplicates, and the same orderings as the declaration demands.
  std::set<std::pair<uint32_t, uint32_t>> seen;
  for (const Edge& e : compiled.edges) {
    if (e.from >= model.nodeCount() || e.to >= model.nodeCount() || !ref.alive[e.from] || !ref.alive[e.to] ||
        e.from == e.to || !seen.insert({e.from, e.to}).second) {
      problems.push_back("bad, culled, self or duplicate edge " + std::to_string(e.from) + "->" + std::to_string(e.to));
    }
  }
  std::vector<Edge> requiredEdges;
  for (const RequiredOrder& r : ref.required) requiredEdges.push_back({r.before, r.after});
  const Reachability viaEdges(model.nodeCount(), compiled.edges);
  const Reachability viaRequired(model.nodeCount(), requiredEdges);
  for (const RequiredOrder& r : ref.required) {
    if (!viaEdges.reaches(r.before, r.after)) problems.push_back("edges miss " + edgeText(model, r.before, r.after));
  }
  for (const Edge& e : compiled.edges) {
    if (e.from < model.nodeCount() && e.to < model.nodeCount() && !viaRequired.reaches(e.from, e.to) &&
        !readersNeedingAChain(model, compiled, e.from, e.to)) {
      problems.push_back("edge not implied by any version " + edgeText(model, e.from, e.to));
    }
  }
  return problems;
}

Problems checkQueuesAndSync(const GraphModel& model, const Reference& ref, const CompiledGraph& compiled,
                            const CompileOptions& options) {
  Problems problems;
  if (compiled.queueCount != options.queueCount) problems.push_back("queueCount differs from options");
  for (uint32_t n : compiled.order) {
    const uint32_t expected = options.queueOfClass[static_cast<size_t>(model.nodeClass[n])];
    if (compiled.nodes[n].queue != expected) problems.push_back("queue of '" + model.nodeName[n] + "'");
  }
  std::set<std::pair<uint32_t, uint32_t>> edgeSet;
  for (const Edge& e : compiled.edges) edgeSet.insert({e.from, e.to});
  std::vector<uint32_t> incoming(model.nodeCount(), 0);
  for (const Edge& e : compiled.syncEdges) {
    if (!edgeSet.contains({e.from, e.to})) problems.push_back("G* edge not a dependency edge");
    if (compiled.nodes[e.from].queue == compiled.nodes[e.to].queue) problems.push_back("G* edge on one queue");
    // Algorithm 3 adds an edge only when it covers at least one more queue.
    if (++incoming[e.to] > options.queueCount - 1) problems.push_back("more than Q-1 G* edges into a node");
  }
  std::vector<Edge> enforced = compiled.syncEdges;
  const std::vector<Edge> chain = sameQueueChain(compiled);
  enforced.insert(enforced.end(), chain.begin(), chain.end());
  const Reachability reach(model.nodeCount(), enforced);
  for (const RequiredOrder& r : ref.required) {
    if (!reach.reaches(r.before, r.after)) {
      problems.push_back("G* + queue order lose " + edgeText(model, r.before, r.after));
    }
  }
  return problems;
}

std::string joinProblems(const Problems& problems, size_t limit) {
  std::ostringstream out;
  for (size_t i = 0; i < problems.size() && i < limit; ++i) out << "\n  - " << problems[i];
  if (problems.size() > limit) out << "\n  ... " << problems.size() - limit << " more";
  return out.str();
}

Problems checkEverything(const GraphModel& model, const FrameGraph& graph, const Reference& ref,
                         const CompiledGraph& compiled, const CompileOptions& options) {
  Problems all;
  auto append = [&all](const Problems& some) { all.insert(all.end(), some.begin(), some.end()); };
  append(checkCulling(model, graph, ref, compiled));
  if (!all.empty()) return all;  // later checks assume the alive set is right
  append(checkOrderAndLevels(model, ref, compiled));
  if (!all.empty()) return all;
  append(checkQueuesAndSync(model, ref, compiled, options));
  append(checkSubmits(ref, compiled));
  if (!all.empty()) return all;  // memory and barrier checks rely on steps and submits
  append(checkLifetimes(model, compiled));
  append(checkResolvedFields(graph, compiled));
  append(checkAliasing(model, graph, compiled, options));
  append(checkBarriers(model, graph, ref, compiled, options));
  return all;
}

}  // namespace fgb::graph::test
