// Internal: the version walk that turns declared uses into ordering edges. Shared by cycle
// detection (all nodes) and dependency building (alive nodes), so both see the same rules.
#pragma once

#include <algorithm>
#include <span>
#include <utility>

namespace fgb::graph::detail {

// The layout `node` reads `version` in, and whether that use also writes (a read-write use).
inline std::pair<Layout, bool> readerUse(const FrameGraph& graph, uint32_t node, uint32_t version) {
  for (const Use& use : graph.uses(node)) {
    if (use.readVersion == version) return {use.layout, use.writeVersion != kInvalidIndex};
  }
  return {Layout::Undefined, false};
}

// For each resource, versions are visited in creation order (which is the write order). Per version:
//   RAW  producer(v) -> each alive reader of v
//   WAR  each alive reader of the previous alive version -> producer(v)
//   WAW  producer of the previous alive version -> producer(v)
// A culled writer is skipped: its version has no alive readers, so the next alive writer is
// ordered directly after the last alive writer and its readers.
template <typename EmitEdge>
void forEachHazardEdge(const FrameGraph& graph, const std::vector<uint8_t>& alive, const Adjacency& readers,
                       EmitEdge&& emit) {
  const auto& versions = graph.versions();
  ScratchVector<uint32_t> lastAliveVersion(graph.resources().size(), kInvalidIndex);
  for (uint32_t v = 0; v < versions.size(); ++v) {
    const VersionDecl& version = versions[v];
    const uint32_t producer = version.producer;
    if (producer != kInvalidIndex && !alive[producer]) continue;  // culled writer: skipped
    uint32_t& previous = lastAliveVersion[version.resource];
    if (producer != kInvalidIndex && previous != kInvalidIndex) {
      const uint32_t previousProducer = versions[previous].producer;
      if (previousProducer != kInvalidIndex && previousProducer != producer) emit(previousProducer, producer);
      for (uint32_t i = readers.begin(previous); i < readers.end(previous); ++i) {
        if (readers.items[i] != producer) emit(readers.items[i], producer);
      }
    }
    previous = v;
    for (uint32_t i = readers.begin(v); i < readers.end(v); ++i) {
      if (producer != kInvalidIndex && producer != readers.items[i]) emit(producer, readers.items[i]);
    }
  }
}

// Position of each node in one topological order of `edges` (Kahn); nodes on cycles get the
// largest ranks (cycle detection reports them from the hazard edges alone).
inline ScratchVector<uint32_t> topologicalRank(uint32_t nodeCount, std::span<const Edge> edges) {
  ScratchVector<uint32_t> pending(nodeCount, 0);
  ScratchVector<uint32_t> start(nodeCount + 1, 0);
  for (const Edge& e : edges) {
    ++pending[e.to];
    ++start[e.from + 1];
  }
  for (uint32_t n = 1; n <= nodeCount; ++n) start[n] += start[n - 1];
  ScratchVector<uint32_t> succ(edges.size(), 0);
  ScratchVector<uint32_t> cursor(start.begin(), start.end() - 1);
  for (const Edge& e : edges) succ[cursor[e.from]++] = e.to;
  ScratchVector<uint32_t> rank(nodeCount, nodeCount);
  ScratchVector<uint32_t> ready;
  for (uint32_t n = 0; n < nodeCount; ++n) {
    if (pending[n] == 0) ready.push_back(n);
  }
  uint32_t next = 0;
  for (size_t i = 0; i < ready.size(); ++i) {  // FIFO over a growing vector
    const uint32_t n = ready[i];
    rank[n] = next++;
    for (uint32_t s = start[n]; s < start[n + 1]; ++s) {
      if (--pending[succ[s]] == 0) ready.push_back(succ[s]);
    }
  }
  return rank;
}

// Hazard edges plus the reader chains: readers of one version that differ in queue or (textures)
// layout cannot run side by side, since the hand-over (ownership transfer, layout change) is a
// write in disguise. Readers are taken in a topological order of the hazard edges, cut into runs
// of equal (queue, layout), and every reader of a run is ordered before every reader of the next.
// Following a topological order means the chains can never close a cycle the declaration does not
// have; ordering whole runs (not just neighbours) keeps the barrier planner, which walks uses in
// the final order, from handing a resource back and forth without a semaphore. A read-write use
// is the next version's writer: WAR already orders it after every reader, so it is not chained.
// (Reader chains rewritten by the graph-tests helper; see its report.)
// Appends the edges to `edges` (hazard edges first; the rank pass reads them back from there).
inline void appendVersionEdges(const FrameGraph& graph, const std::vector<uint8_t>& alive,
                               const std::vector<uint32_t>& queueOf, const Adjacency& readers,
                               ScratchVector<Edge>& edges) {
  const size_t firstHazard = edges.size();
  forEachHazardEdge(graph, alive, readers, [&](uint32_t from, uint32_t to) { edges.push_back({from, to}); });
  const size_t hazardCount = edges.size() - firstHazard;
  auto emit = [&](uint32_t from, uint32_t to) { edges.push_back({from, to}); };
  // The rank pass is only needed once some version has readers in two different runs; shapes
  // where every version has one reader, or all readers agree, never pay for it.
  ScratchVector<uint32_t> rank;
  struct Reader {
    uint32_t rank, node, queue;
    Layout layout;
  };
  std::vector<Reader> chain;  // scratch, reused per version
  const auto& versions = graph.versions();
  for (uint32_t v = 0; v < versions.size(); ++v) {
    if (readers.end(v) - readers.begin(v) < 2) continue;
    const bool texture = graph.resources()[versions[v].resource].kind == ResourceKind::Texture;
    chain.clear();
    for (uint32_t i = readers.begin(v); i < readers.end(v); ++i) {
      const uint32_t node = readers.items[i];
      const auto [layout, alsoWrites] = readerUse(graph, node, v);
      if (!alsoWrites) chain.push_back({0, node, queueOf[node], texture ? layout : Layout::General});
    }
    auto sameRun = [](const Reader& a, const Reader& b) { return a.queue == b.queue && a.layout == b.layout; };
    const bool oneRun = std::all_of(chain.begin(), chain.end(), [&](const Reader& r) { return sameRun(r, chain[0]); });
    if (oneRun) continue;  // a single run has no neighbouring run to order against
    if (rank.empty()) {
      rank = topologicalRank(static_cast<uint32_t>(graph.nodes().size()),
                             std::span<const Edge>(edges.data() + firstHazard, hazardCount));
    }
    for (Reader& reader : chain) reader.rank = rank[reader.node];
    std::sort(chain.begin(), chain.end(), [](const Reader& a, const Reader& b) { return a.rank < b.rank; });
    // Runs [runStart, runEnd) and [runEnd, nextEnd): all-to-all edges between neighbouring runs.
    for (size_t runStart = 0, runEnd = 0; runStart < chain.size(); runStart = runEnd) {
      for (runEnd = runStart + 1; runEnd < chain.size() && sameRun(chain[runEnd], chain[runStart]);) ++runEnd;
      size_t nextEnd = runEnd;
      while (nextEnd < chain.size() && sameRun(chain[nextEnd], chain[runEnd])) ++nextEnd;
      for (size_t a = runStart; a < runEnd; ++a) {
        for (size_t b = runEnd; b < nextEnd; ++b) {
          if (chain[a].node != chain[b].node) emit(chain[a].node, chain[b].node);
        }
      }
    }
  }
}

}  // namespace fgb::graph::detail
