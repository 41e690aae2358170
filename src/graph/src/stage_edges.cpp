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
// All of it is one walk over the alive nodes in a topological order, each node looking back at
// what it depends on. Declaration order is such an order unless some node read an old version
// (FrameGraph::readsOldVersions); only then is an order computed first, which also finds cycles.
#include "compile_state.hpp"

#include <algorithm>
#include <string>

namespace fgb::graph::detail {

// (Declared in compile_state.hpp: CullDiagnostics indexes the same way.)
void indexVersionReaders(const FrameGraph& graph, std::vector<uint32_t>& start, std::vector<uint32_t>& readers) {
  start.assign(graph.versions().size() + 1, 0);
  for (const Use& use : graph.allUses()) {
    if (use.readVersion != kInvalidIndex) ++start[use.readVersion + 1];
  }
  for (size_t v = 1; v < start.size(); ++v) start[v] += start[v - 1];
  readers.resize(start.back());
  ScratchVector<uint32_t> cursor(start.begin(), start.end() - 1);
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  for (uint32_t n = 0; n < nodeCount; ++n) {
    for (const Use& use : graph.uses(n)) {
      if (use.readVersion != kInvalidIndex) readers[cursor[use.readVersion]++] = n;
    }
  }
}

namespace {

// ---- Topological order and cycles, for declarations with old-version reads -------------------

// Predecessor lists of every declared node from the version edges alone (no reader chains, which
// follow an order that only exists once these are acyclic).
Adjacency versionEdgePredecessors(const FrameGraph& graph) {
  Adjacency readers;
  indexVersionReaders(graph, readers.start, readers.items);
  const auto& versions = graph.versions();
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  ScratchVector<Edge> edges;
  for (uint32_t v = 0; v < versions.size(); ++v) {
    const uint32_t producer = versions[v].producer;
    const uint32_t previous = versions[v].previous;
    if (producer != kInvalidIndex && previous != kInvalidIndex) {
      const uint32_t previousProducer = versions[previous].producer;
      if (previousProducer != kInvalidIndex && previousProducer != producer) {
        edges.push_back({previousProducer, producer});
      }
      for (uint32_t i = readers.begin(previous); i < readers.end(previous); ++i) {
        if (readers.items[i] != producer) edges.push_back({readers.items[i], producer});
      }
    }
    for (uint32_t i = readers.begin(v); i < readers.end(v); ++i) {
      if (producer != kInvalidIndex && producer != readers.items[i]) edges.push_back({producer, readers.items[i]});
    }
  }
  Adjacency preds;
  preds.start.assign(nodeCount + 1, 0);
  for (const Edge& e : edges) ++preds.start[e.to + 1];
  for (uint32_t n = 1; n <= nodeCount; ++n) preds.start[n] += preds.start[n - 1];
  preds.items.resize(edges.size());
  ScratchVector<uint32_t> cursor(preds.start.begin(), preds.start.end() - 1);
  for (const Edge& e : edges) preds.items[cursor[e.to]++] = e.from;
  return preds;
}

// Throws GraphError naming a cycle among `left` (nodes Kahn's algorithm could not order).
[[noreturn]] void reportCycle(const FrameGraph& graph, const Adjacency& preds, const std::vector<uint32_t>& left) {
  // Every node left over has a predecessor that is also left over: walk predecessors until a
  // node repeats; the walk from its first visit is a cycle.
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  std::vector<uint8_t> isLeft(nodeCount, 0);
  for (uint32_t n : left) isLeft[n] = 1;
  std::vector<uint32_t> visitedAt(nodeCount, kInvalidIndex);
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
  for (uint32_t n : cycle) names.append("'").append(graph.nodes()[n].name).append("' -> ");
  names.append("'").append(graph.nodes()[cycle.front()].name).append("'");
  throw GraphError("frame graph has a cycle: " + names);
}

// Every declared node in a topological order of the version edges (Kahn, FIFO); throws on a cycle.
ScratchVector<uint32_t> topologicalOrder(const FrameGraph& graph) {
  const auto nodeCount = static_cast<uint32_t>(graph.nodes().size());
  const Adjacency preds = versionEdgePredecessors(graph);
  Adjacency succs;
  succs.start.assign(nodeCount + 1, 0);
  for (uint32_t p : preds.items) ++succs.start[p + 1];
  for (uint32_t n = 1; n <= nodeCount; ++n) succs.start[n] += succs.start[n - 1];
  succs.items.resize(preds.items.size());
  ScratchVector<uint32_t> cursor(succs.start.begin(), succs.start.end() - 1);
  ScratchVector<uint32_t> pending(nodeCount, 0);
  ScratchVector<uint32_t> order;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    pending[n] = preds.end(n) - preds.begin(n);
    if (pending[n] == 0) order.push_back(n);
    for (uint32_t i = preds.begin(n); i < preds.end(n); ++i) succs.items[cursor[preds.items[i]]++] = n;
  }
  for (size_t i = 0; i < order.size(); ++i) {  // FIFO over a growing vector
    const uint32_t n = order[i];
    for (uint32_t s = succs.begin(n); s < succs.end(n); ++s) {
      if (--pending[succs.items[s]] == 0) order.push_back(succs.items[s]);
    }
  }
  if (order.size() < nodeCount) {
    std::vector<uint32_t> left;
    for (uint32_t n = 0; n < nodeCount; ++n) {
      if (pending[n] != 0) left.push_back(n);
    }
    reportCycle(graph, preds, left);
  }
  return order;
}

// ---- The dependency walk ----------------------------------------------------------------------

// Visits alive nodes in a topological order; each visit records the node's dependencies (edges
// into it) and its level, from what earlier visits recorded about the versions they read.
class DependencyWalk {
 public:
  explicit DependencyWalk(CompileState& state)
      : state_(state), graph_(state.graph), versions_(state.graph.versions()),
        seenFor_(state.nodeCount, kInvalidIndex) {
    // Reader lists start empty when their version is written (see visitWrite), which is just
    // before its readers look at them: set up front, every one would have left the cache by then.
    // Only imports' first versions are read without a write in the graph.
    readers_.resize(versions_.size());  // constructs nothing (see VersionReaders)
    const auto& resources = graph_.resources();
    for (uint32_t r = 0; r < state.resourceCount; ++r) {
      if (state.isImported(r)) readers_[resources[r].firstVersion] = VersionReaders::none();
    }
    state.edgeStart.assign(state.nodeCount, 0);
    state.edgeEnd.assign(state.nodeCount, 0);
    state.level.assign(state.nodeCount, 0);
    state.out.edges.reserve(graph_.allUses().size());  // about one edge per read
    reads_.reserve(graph_.allUses().size());
  }

  void visit(uint32_t node) {
    node_ = node;
    level_ = 0;
    state_.edgeStart[node] = static_cast<uint32_t>(state_.out.edges.size());
    for (const Use& use : graph_.uses(node)) {
      if (use.readVersion != kInvalidIndex) visitRead(use);
      if (use.writeVersion != kInvalidIndex) visitWrite(use);
    }
    state_.edgeEnd[node] = static_cast<uint32_t>(state_.out.edges.size());
    state_.level[node] = level_;
    state_.maxLevel = std::max(state_.maxLevel, level_);
  }

 private:
  // What the walk knows about a version's alive readers so far: all of them (`newest`, a list
  // linked through reads_, newest first), and the current and previous run of the reader chain
  // (lists of the same kind). Set up when the version is written (visitWrite) rather than at its
  // first read: whether a read is its version's first is as good as random, and a branch on it
  // cost more than writing the entries.
  struct VersionReaders {
    // NOLINTNEXTLINE(modernize-use-equals-default,cppcoreguidelines-pro-type-member-init): unset on purpose
    VersionReaders() {}
    static VersionReaders none() {
      VersionReaders r;
      r.newest = r.newestNode = r.run = r.previousRun = kInvalidIndex;
      r.runKey = 0;
      return r;
    }
    uint32_t newest;
    uint32_t newestNode;  // reads_[newest].node, without the load
    uint32_t run;
    uint32_t previousRun;
    uint32_t runKey;  // queue and layout the current run shares (while there is one)
  };
  struct Read {
    uint32_t node;
    uint32_t nextOfVersion;  // older reader of the same version
    uint32_t nextInRun;      // older reader of the same run
  };

  void dependOn(uint32_t predecessor) {
    if (predecessor == node_ || seenFor_[predecessor] == node_) return;  // no self-loops or duplicates
    seenFor_[predecessor] = node_;
    state_.out.edges.push_back({predecessor, node_});
    level_ = std::max(level_, state_.level[predecessor] + 1);
  }
  void dependOnList(uint32_t read, uint32_t Read::*next) {
    for (; read != kInvalidIndex; read = reads_[read].*next) dependOn(reads_[read].node);
  }

  // Whether a read starts a new run is as good as random: the run bookkeeping is selected with a
  // mask rather than branched on (a conditional expression compiles to a branch here).
  void visitRead(const Use& use) {
    const uint32_t version = use.readVersion;
    if (use.readProducer != kInvalidIndex) dependOn(use.readProducer);  // RAW
    VersionReaders& readers = readers_[version];
    // One entry per (node, version), like the node's first use of it (a node may read it twice).
    if (readers.newestNode == node_) return;
    const auto read = static_cast<uint32_t>(reads_.size());
    reads_.emplace_back(node_, readers.newest, kInvalidIndex);  // in place: see add() in stage_barriers.cpp
    readers.newest = read;
    readers.newestNode = node_;
    if (use.writeVersion != kInvalidIndex) return;  // a read-write use is not chained (see above)
    const bool texture = state_.isTexture(use.resource);
    const uint32_t key = state_.queueOf[node_] << 8 | static_cast<uint32_t>(texture ? use.layout : Layout::General);
    const uint32_t run = readers.run;
    // All ones if another key's run is current (this reader starts the next run), else 0.
    const uint32_t startsNextRun = 0u - static_cast<uint32_t>((run != kInvalidIndex) & (readers.runKey != key));
    readers.previousRun = (run & startsNextRun) | (readers.previousRun & ~startsNextRun);
    dependOnList(readers.previousRun, &Read::nextInRun);  // after every reader of the run before
    reads_[read].nextInRun = run | startsNextRun;  // kInvalidIndex (all ones) when it starts the next run
    readers.run = read;
    readers.runKey = key;
  }

  void visitWrite(const Use& use) {
    const uint32_t version = use.writeVersion;
    readers_[version] = VersionReaders::none();
    // The previous alive version: versions of culled writers have no alive readers; skip them.
    uint32_t previous = versions_[version].previous;
    while (previous != kInvalidIndex && versions_[previous].producer != kInvalidIndex &&
           !state_.alive[versions_[previous].producer]) {
      previous = versions_[previous].previous;
    }
    if (previous == kInvalidIndex) return;
    if (versions_[previous].producer != kInvalidIndex) {
      dependOn(versions_[previous].producer);  // WAW
    } else if (!state_.isImported(use.resource)) {
      return;  // a transient's first version: nobody can have read it (reads need a writer)
    }
    dependOnList(readers_[previous].newest, &Read::nextOfVersion);  // WAR
  }

  CompileState& state_;
  const FrameGraph& graph_;
  const std::vector<VersionDecl>& versions_;
  ScratchVector<VersionReaders> readers_;  // per version
  ScratchVector<Read> reads_;
  ScratchVector<uint32_t> seenFor_;        // per node: the last node that depended on it
  uint32_t node_ = kInvalidIndex;          // the node being visited...
  uint32_t level_ = 0;                     // ...and its level so far
};

}  // namespace

void buildDependencies(CompileState& state) {
  DependencyWalk walk(state);
  if (!state.graph.readsOldVersions()) {
    // The alive nodes listed first, without a branch: which nodes were culled is as good as random,
    // and a branch on it in the walk below would be mispredicted about once per culled node.
    ScratchVector<uint32_t> aliveNodes(state.nodeCount, 0);
    uint32_t aliveCount = 0;
    for (uint32_t n = 0; n < state.nodeCount; ++n) {
      aliveNodes[aliveCount] = n;
      aliveCount += state.alive[n];
    }
    for (uint32_t i = 0; i < aliveCount; ++i) walk.visit(aliveNodes[i]);
    return;
  }
  for (const uint32_t n : topologicalOrder(state.graph)) {
    if (state.alive[n]) walk.visit(n);
  }
}

}  // namespace fgb::graph::detail
