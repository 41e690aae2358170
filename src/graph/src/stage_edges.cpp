// Stage: the dependency edges among alive nodes (deduplicated, as CompiledGraph::edges grouped by
// target), their longest-path levels, and cycle detection over every declared node.
//
// Versions order nodes (see frame_graph.hpp):
//   RAW  producer(v) -> each alive reader of v
//   WAR  each alive reader of the previous alive version -> producer(v)
//   WAW  producer of the previous alive version -> producer(v)
// A culled writer is skipped: its version has no alive readers, so the next alive writer is
// ordered directly after the last alive writer and its readers.
//
// Reader chains come on top: readers of one version that differ in queue or (textures) layout
// cannot run side by side, since the hand-over (ownership transfer, layout change) is a write in
// disguise. Readers are taken in a topological order of the version edges, cut into runs of equal
// (queue, layout), and every reader of a run is ordered before every reader of the next.
// Following a topological order means the chains can never close a cycle the declaration does not
// have; ordering whole runs (not just neighbours) keeps the barrier planner, which walks uses in
// the final order, from handing a resource back and forth without a semaphore. A read-write use
// is the next version's writer: WAR already orders it after every reader, so it is not chained.
//
// All of it is one walk over the alive nodes in a topological order of the version edges, each node
// looking back at what it depends on. Declaration order is such an order unless some node read a
// version after another node had written over it (WAR then points back); only then is an order
// computed (Kahn), which also finds cycles.
#include <algorithm>
#include <string>

#include "compile_state.hpp"

namespace fgb::graph::detail {

void indexVersionReaders(const FrameGraph& graph, std::vector<uint32_t>& start, std::vector<uint32_t>& readers) {
  start.assign(Declared::versions(graph).size() + 1, 0);
  for (const Use& use : Declared::allUses(graph)) {
    if (use.reads()) ++start[use.readVersion + 1];
  }
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  readers.resize(start.back());
  std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
  for (uint32_t n = 0; n < graph.nodes().size(); ++n) {
    for (const Use& use : Declared::uses(graph, n)) {
      if (use.reads()) readers[cursor[use.readVersion]++] = n;
    }
  }
}

namespace {

using NodeLists = std::vector<std::vector<uint32_t>>;  // per node, a list of nodes

// ---- Topological order and cycles -----------------------------------------------------------

// Predecessors of every declared node along the version edges alone (no reader chains, which
// follow an order that only exists once these are acyclic).
NodeLists versionEdgePredecessors(const FrameGraph& graph) {
  std::vector<uint32_t> readerStart;
  std::vector<uint32_t> readers;
  indexVersionReaders(graph, readerStart, readers);
  const auto& versions = Declared::versions(graph);
  NodeLists preds(graph.nodes().size());
  auto addEdge = [&](uint32_t from, uint32_t to) {
    if (from != to) preds[to].push_back(from);
  };
  for (uint32_t v = 0; v < versions.size(); ++v) {
    const uint32_t producer = versions[v].producer;
    const uint32_t previous = versions[v].previous;
    if (producer == kInvalidIndex) continue;  // a resource's first version
    if (previous != kInvalidIndex) {
      if (versions[previous].producer != kInvalidIndex) addEdge(versions[previous].producer, producer);  // WAW
      for (uint32_t i = readerStart[previous]; i < readerStart[previous + 1]; ++i) addEdge(readers[i], producer);
    }
    for (uint32_t i = readerStart[v]; i < readerStart[v + 1]; ++i) addEdge(producer, readers[i]);  // RAW
  }
  return preds;
}

// Throws GraphError naming a cycle among the nodes Kahn's algorithm left over (those still
// `pending` predecessors).
[[noreturn]] void reportCycle(const FrameGraph& graph, const NodeLists& preds, const std::vector<uint32_t>& pending) {
  // Every node left over has a predecessor that is also left over: walk predecessors until a
  // node repeats; the walk from its first visit is a cycle.
  std::vector<uint32_t> visitedAt(graph.nodes().size(), kInvalidIndex);
  std::vector<uint32_t> walk;
  auto node = static_cast<uint32_t>(std::find_if(pending.begin(), pending.end(), [](uint32_t p) { return p != 0; }) -
                                    pending.begin());
  while (visitedAt[node] == kInvalidIndex) {
    visitedAt[node] = static_cast<uint32_t>(walk.size());
    walk.push_back(node);
    node = *std::find_if(preds[node].begin(), preds[node].end(), [&](uint32_t p) { return pending[p] != 0; });
  }
  std::vector<uint32_t> cycle(walk.begin() + visitedAt[node], walk.end());
  std::reverse(cycle.begin(), cycle.end());  // the walk followed predecessors
  std::string names;
  for (uint32_t n : cycle) names.append("'").append(graph.nodes()[n].name).append("' -> ");
  names.append("'").append(graph.nodes()[cycle.front()].name).append("'");
  throw GraphError("frame graph has a cycle: " + names);
}

// Every declared node in a topological order of the version edges: declaration order when every
// edge points forward, else Kahn's (FIFO). Throws on a cycle.
std::vector<uint32_t> topologicalOrder(const FrameGraph& graph) {
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  const NodeLists preds = versionEdgePredecessors(graph);
  std::vector<uint32_t> order(nodeCount);
  bool forward = true;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    order[n] = n;
    for (const uint32_t p : preds[n]) forward = forward && p < n;
  }
  if (forward) return order;
  NodeLists succs(nodeCount);
  std::vector<uint32_t> pending(nodeCount);
  order.clear();
  for (uint32_t n = 0; n < nodeCount; ++n) {
    pending[n] = static_cast<uint32_t>(preds[n].size());
    if (pending[n] == 0) order.push_back(n);
    for (const uint32_t p : preds[n]) succs[p].push_back(n);
  }
  for (size_t i = 0; i < order.size(); ++i) {  // FIFO over a growing vector
    for (const uint32_t s : succs[order[i]]) {
      if (--pending[s] == 0) order.push_back(s);
    }
  }
  if (order.size() < nodeCount) reportCycle(graph, preds, pending);
  return order;
}

// ---- The dependency walk ----------------------------------------------------------------------

// Visits alive nodes in a topological order; each visit records the node's dependencies (edges
// into it) and its level, from what earlier visits recorded about the versions they read.
class DependencyWalk {
 public:
  explicit DependencyWalk(CompileState& state)
      : state_(state),
        versions_(state.versions()),
        readers_(versions_.size()),
        seenFor_(state.nodeCount, kInvalidIndex) {
    state.edgeStart.assign(state.nodeCount, 0);
    state.edgeEnd.assign(state.nodeCount, 0);
    state.maxLevel = 0;
    state.out.edges.clear();
  }

  void visit(uint32_t node) {
    node_ = node;
    level_ = 0;
    state_.edgeStart[node] = static_cast<uint32_t>(state_.out.edges.size());
    for (const Use& use : state_.uses(node)) {
      if (use.reads()) visitRead(use);
      if (use.writes()) visitWrite(use);
    }
    state_.edgeEnd[node] = static_cast<uint32_t>(state_.out.edges.size());
    state_.out.nodes[node].level = level_;
    state_.maxLevel = std::max(state_.maxLevel, level_);
  }

 private:
  // The alive readers of a version visited so far, in visit order, each node once: all of them (for
  // WAR), and those that are chained (not read-write), in runs of equal (queue, layout) key.
  struct VersionReaders {
    std::vector<uint32_t> all;
    std::vector<uint32_t> chained;
    uint32_t runBegin = 0;          // chained[runBegin ..) is the current run...
    uint32_t previousRunBegin = 0;  // ...and chained[previousRunBegin .. runBegin) the one before
    uint32_t runKey = 0;
  };

  void dependOn(uint32_t predecessor) {
    if (predecessor == node_ || seenFor_[predecessor] == node_) return;  // no self-loops or duplicates
    seenFor_[predecessor] = node_;
    state_.out.edges.push_back({predecessor, node_});
    level_ = std::max(level_, state_.out.nodes[predecessor].level + 1);
  }
  // Newest first.
  void dependOnAll(const std::vector<uint32_t>& nodes, size_t begin, size_t end) {
    for (size_t i = end; i-- > begin;) dependOn(nodes[i]);
  }

  void visitRead(const Use& use) {
    const uint32_t producer = versions_[use.readVersion].producer;
    if (producer != kInvalidIndex) dependOn(producer);  // RAW
    VersionReaders& readers = readers_[use.readVersion];
    if (!readers.all.empty() && readers.all.back() == node_) return;  // the node's second use of it
    readers.all.push_back(node_);
    if (use.writes()) return;  // a read-write use is not chained (see above)
    const Layout layout = state_.isTexture(use.resource) ? use.layout : Layout::General;
    const uint32_t key = state_.queueOf[node_] << 8 | static_cast<uint32_t>(layout);
    if (!readers.chained.empty() && readers.runKey != key) {  // this reader starts the next run
      readers.previousRunBegin = readers.runBegin;
      readers.runBegin = static_cast<uint32_t>(readers.chained.size());
    }
    dependOnAll(readers.chained, readers.previousRunBegin, readers.runBegin);  // after the run before
    readers.chained.push_back(node_);
    readers.runKey = key;
  }

  void visitWrite(const Use& use) {
    // The previous alive version: versions of culled writers have no alive readers; skip them.
    uint32_t previous = versions_[use.writeVersion].previous;
    while (previous != kInvalidIndex && versions_[previous].producer != kInvalidIndex &&
           !state_.alive[versions_[previous].producer]) {
      previous = versions_[previous].previous;
    }
    if (previous == kInvalidIndex) return;
    if (versions_[previous].producer != kInvalidIndex) dependOn(versions_[previous].producer);  // WAW
    const std::vector<uint32_t>& readers = readers_[previous].all;
    dependOnAll(readers, 0, readers.size());  // WAR
  }

  CompileState& state_;
  const std::vector<VersionDecl>& versions_;
  std::vector<VersionReaders> readers_;  // per version
  std::vector<uint32_t> seenFor_;        // per node: the last node that depended on it
  uint32_t node_ = kInvalidIndex;        // the node being visited...
  uint32_t level_ = 0;                   // ...and its level so far
};

}  // namespace

void buildDependencies(CompileState& state) {
  DependencyWalk walk(state);
  for (const uint32_t n : topologicalOrder(state.graph)) {
    if (state.alive[n]) walk.visit(n);
  }
}

}  // namespace fgb::graph::detail
