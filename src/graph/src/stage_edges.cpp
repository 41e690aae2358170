// Stages: queue assignment, cycle detection (over every declared node) and the dependency edges
// among alive nodes (deduplicated, as a predecessor adjacency and as CompiledGraph::edges).
#include "compile_state.hpp"

#include <algorithm>
#include <string>

namespace fgb::graph::detail {

Adjacency collectVersionReaders(const FrameGraph& graph, const std::vector<uint8_t>& alive) {
  Adjacency readers;
  readers.start.assign(graph.versions().size() + 1, 0);
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  for (uint32_t n = 0; n < nodeCount; ++n) {
    if (!alive[n]) continue;
    for (const Use& use : graph.uses(n)) {
      if (use.readVersion != kInvalidIndex) ++readers.start[use.readVersion + 1];
    }
  }
  for (size_t v = 1; v < readers.start.size(); ++v) readers.start[v] += readers.start[v - 1];
  readers.items.resize(readers.start.back());
  ScratchVector<uint32_t> cursor(readers.start.begin(), readers.start.end() - 1);
  for (uint32_t n = 0; n < nodeCount; ++n) {
    if (!alive[n]) continue;
    for (const Use& use : graph.uses(n)) {
      if (use.readVersion != kInvalidIndex) readers.items[cursor[use.readVersion]++] = n;
    }
  }
  return readers;
}

void assignQueues(CompileState& state) {
  state.queueOf.resize(state.nodeCount);
  state.out.nodes.resize(state.nodeCount);
  for (uint32_t n = 0; n < state.nodeCount; ++n) {
    const auto queueClass = static_cast<size_t>(state.graph.nodes()[n].queue);
    state.queueOf[n] = state.options.queueOfClass[queueClass];
    state.out.nodes[n].queue = state.queueOf[n];
  }
}

namespace {

// Builds a predecessor adjacency from (from, to) pairs, dropping duplicates.
Adjacency predecessorsFromEdges(uint32_t nodeCount, const std::vector<Edge>& edges, std::vector<Edge>* unique) {
  Adjacency preds;
  preds.start.assign(nodeCount + 1, 0);
  for (const Edge& e : edges) ++preds.start[e.to + 1];
  for (uint32_t n = 1; n <= nodeCount; ++n) preds.start[n] += preds.start[n - 1];
  preds.items.resize(edges.size());
  ScratchVector<uint32_t> cursor(preds.start.begin(), preds.start.end() - 1);
  for (const Edge& e : edges) preds.items[cursor[e.to]++] = e.from;

  // Deduplicate each node's list in place with a "last seen for" stamp per source node.
  ScratchVector<uint32_t> seenFor(nodeCount, kInvalidIndex);
  uint32_t write = 0;
  uint32_t begin = 0;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    const uint32_t end = preds.start[n + 1];
    preds.start[n] = write;
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t from = preds.items[i];
      if (seenFor[from] == n) continue;
      seenFor[from] = n;
      preds.items[write++] = from;
      if (unique != nullptr) unique->push_back({from, n});
    }
    begin = end;
  }
  preds.start[nodeCount] = write;
  preds.items.resize(write);
  return preds;
}

ScratchVector<Edge> versionEdges(const FrameGraph& graph, const std::vector<uint8_t>& alive,
                               const std::vector<uint32_t>& queueOf) {
  const Adjacency readers = collectVersionReaders(graph, alive);
  ScratchVector<Edge> edges;
  edges.reserve(graph.allUses().size() * 2);
  appendVersionEdges(graph, alive, queueOf, readers, edges);
  return edges;
}

// Kahn's algorithm; returns the nodes left with unprocessed predecessors (empty when acyclic).
std::vector<uint32_t> nodesOnOrBehindCycles(uint32_t nodeCount, const Adjacency& preds) {
  ScratchVector<uint32_t> pending(nodeCount, 0);
  Adjacency succs;
  succs.start.assign(nodeCount + 1, 0);
  for (uint32_t n = 0; n < nodeCount; ++n) {
    pending[n] = preds.end(n) - preds.begin(n);
    for (uint32_t i = preds.begin(n); i < preds.end(n); ++i) ++succs.start[preds.items[i] + 1];
  }
  for (uint32_t n = 1; n <= nodeCount; ++n) succs.start[n] += succs.start[n - 1];
  succs.items.resize(preds.items.size());
  ScratchVector<uint32_t> cursor(succs.start.begin(), succs.start.end() - 1);
  for (uint32_t n = 0; n < nodeCount; ++n) {
    for (uint32_t i = preds.begin(n); i < preds.end(n); ++i) succs.items[cursor[preds.items[i]]++] = n;
  }
  ScratchVector<uint32_t> ready;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    if (pending[n] == 0) ready.push_back(n);
  }
  while (!ready.empty()) {
    const uint32_t n = ready.back();
    ready.pop_back();
    for (uint32_t i = succs.begin(n); i < succs.end(n); ++i) {
      if (--pending[succs.items[i]] == 0) ready.push_back(succs.items[i]);
    }
  }
  std::vector<uint32_t> left;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    if (pending[n] != 0) left.push_back(n);
  }
  return left;
}

}  // namespace

namespace {

// Declaration order is almost a topological order of the all-node edges: a producer is declared
// before its readers, and a version's writer after the previous one. The only edges that can point
// backwards are WAR edges from a node that reads a version after its successor's writer was
// declared (an old-version read). Reader chains follow a topological order of the hazard edges, so
// they cannot close a cycle on their own. Without such a read the whole declaration is acyclic.
bool mayHaveCycle(const FrameGraph& graph) {
  const auto& versions = graph.versions();
  std::vector<uint32_t> nextWriter(versions.size(), kInvalidIndex);  // producer of the version over v
  for (const VersionDecl& version : versions) {
    if (version.previous != kInvalidIndex) nextWriter[version.previous] = version.producer;
  }
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  for (uint32_t n = 0; n < nodeCount; ++n) {
    for (const Use& use : graph.uses(n)) {
      if (use.readVersion != kInvalidIndex && nextWriter[use.readVersion] < n) return true;
    }
  }
  return false;
}

}  // namespace

void detectCycles(const CompileState& state) {
  if (!mayHaveCycle(state.graph)) return;
  const std::vector<uint8_t> everyNode(state.nodeCount, 1);
  const Adjacency preds =
      predecessorsFromEdges(state.nodeCount, versionEdges(state.graph, everyNode, state.queueOf), nullptr);
  const std::vector<uint32_t> left = nodesOnOrBehindCycles(state.nodeCount, preds);
  if (!left.empty()) reportCycle(state, preds, left);
}

void reportCycle(const CompileState& state, const Adjacency& preds, const std::vector<uint32_t>& left) {
  // Every node left over has a predecessor that is also left over: walk predecessors until a
  // node repeats; the walk from its first visit is a cycle.
  std::vector<uint8_t> isLeft(state.nodeCount, 0);
  for (uint32_t n : left) isLeft[n] = 1;
  std::vector<uint32_t> visitedAt(state.nodeCount, kInvalidIndex);
  std::vector<uint32_t> walk;
  uint32_t node = left.front();
  while (visitedAt[node] == kInvalidIndex) {
    visitedAt[node] = static_cast<uint32_t>(walk.size());
    walk.push_back(node);
    for (uint32_t i = preds.begin(node); i < preds.end(node); ++i) {
      if (isLeft[preds.items[i]]) {
        node = preds.items[i];
        break;
      }
    }
  }
  std::vector<uint32_t> cycle(walk.begin() + visitedAt[node], walk.end());
  std::reverse(cycle.begin(), cycle.end());  // the walk followed predecessors
  std::string names;
  for (uint32_t n : cycle) names += "'" + state.graph.nodes()[n].name + "' -> ";
  names += "'" + state.graph.nodes()[cycle.front()].name + "'";
  throw GraphError("frame graph has a cycle: " + names);
}

void buildDependencies(CompileState& state) {
  const ScratchVector<Edge> edges = versionEdges(state.graph, state.alive, state.queueOf);
  state.out.edges.reserve(edges.size());
  state.predecessors = predecessorsFromEdges(state.nodeCount, edges, &state.out.edges);
}

}  // namespace fgb::graph::detail
