// Internal: state shared by the compiler stages (one file per stage, run in order by compiler.cpp).
#pragma once

#include "vector_pool.hpp"

#include <fgb/graph/compiler.hpp>

#include <array>
#include <cstdint>
#include <iterator>
#include <vector>

namespace fgb::graph::detail {

using QueueArray = std::array<uint32_t, kQueueClassCount>;

// A std::vector whose storage comes from, and goes back to, a per-thread pool (see
// vector_pool.hpp). Only for temporaries: results handed to the caller are plain vectors.
template <typename T>
class ScratchVector : public std::vector<T> {
 public:
  ScratchVector() { VectorPool<T>::take(*this); }
  ScratchVector(size_t count, const T& value) : ScratchVector() { this->assign(count, value); }
  template <std::input_iterator It>
  ScratchVector(It first, It last) : ScratchVector() {
    this->assign(first, last);
  }
  ScratchVector(const ScratchVector&) = delete;
  ScratchVector& operator=(const ScratchVector&) = delete;
  ScratchVector(ScratchVector&& other) noexcept : std::vector<T>(std::move(other)) {}
  ScratchVector& operator=(ScratchVector&& other) noexcept {
    std::vector<T>::swap(other);
    return *this;
  }
  ~ScratchVector() { VectorPool<T>::give(*this); }
};

// Compressed adjacency by index: the neighbours of i are items[start[i] .. start[i+1]).
struct Adjacency {
  ScratchVector<uint32_t> start;
  ScratchVector<uint32_t> items;
  [[nodiscard]] uint32_t begin(uint32_t i) const { return start[i]; }
  [[nodiscard]] uint32_t end(uint32_t i) const { return start[i + 1]; }
};

// The readers of each version among all declared nodes: readers[start[v] .. start[v + 1]) read
// version v, in declaration order, a node once per use of it (so one that reads v twice is listed
// twice, next to itself). Used by the dependency stage (for declarations with old-version reads)
// and by CullDiagnostics.
void indexVersionReaders(const FrameGraph& graph, std::vector<uint32_t>& start, std::vector<uint32_t>& readers);

// Per resource, the facts later stages test for every use, packed densely (ResourceDecl is large).
enum ResourceTraits : uint8_t {
  kResourceTexture = 1u << 0,
  kResourceImported = 1u << 1,
};

// Where a node stands among the queues, for SSIS and placement: σ(u) = order position + queue·V + 1
// (V alive nodes) numbers each queue's nodes contiguously, so σ alone also tells u's queue; `known`
// holds, per queue, the largest σ that u is ordered after. One record per node: SSIS reads both
// for every dependency, which then costs one load.
struct alignas(16) SyncPoint {
  QueueArray known;
  uint32_t sigma;
};

struct CompileState {
  CompileState(const FrameGraph& g, const CompileOptions& o, CompiledGraph& c)
      : graph(g), options(o), out(c), nodeCount(static_cast<uint32_t>(g.nodes().size())),
        resourceCount(static_cast<uint32_t>(g.resources().size())), queueCount(o.queueCount) {}

  const FrameGraph& graph;
  const CompileOptions& options;
  CompiledGraph& out;
  uint32_t nodeCount;
  uint32_t resourceCount;
  uint32_t queueCount;

  ScratchVector<uint8_t> resourceTraits;  // per resource: ResourceTraits bits
  [[nodiscard]] bool isImported(uint32_t resource) const { return (resourceTraits[resource] & kResourceImported) != 0; }
  [[nodiscard]] bool isTexture(uint32_t resource) const { return (resourceTraits[resource] & kResourceTexture) != 0; }
  [[nodiscard]] ResourceKind kindOf(uint32_t resource) const {
    return isTexture(resource) ? ResourceKind::Texture : ResourceKind::Buffer;
  }
  ScratchVector<uint8_t> alive;           // per node
  ScratchVector<uint32_t> aliveUses;      // per resource: how many uses alive nodes make of it
  bool anyCulled = false;
  ScratchVector<uint32_t> queueOf;        // per node: queue index
  // Per node: its dependencies are out.edges[edgeStart[n] .. edgeEnd[n]) (the edges into n).
  ScratchVector<uint32_t> edgeStart;
  ScratchVector<uint32_t> edgeEnd;
  ScratchVector<uint32_t> level;          // per node: longest-path level (alive nodes)
  uint32_t maxLevel = 0;
  ScratchVector<SyncPoint> sync;          // per node, with several queues (see SyncPoint)
};

// Stages, in pipeline order.
void resolveResources(CompileState& state);      // dependent fields, resourceTraits
void cullNodes(CompileState& state);             // queues, alive + NodeInfo reasons, aliveUses
void buildDependencies(CompileState& state);     // RAW/WAR/WAW + reader-chain edges, levels; cycles
void sortByLevel(CompileState& state);           // order
void pruneCrossQueueEdges(CompileState& state);  // SSIS → syncEdges, known
void placeSubmits(CompileState& state);          // steps + submits + waits
// Lifetimes, memory requirements, aliasing plan and barriers, in one walk over the order.
void placeAndPlanBarriers(CompileState& state);

}  // namespace fgb::graph::detail
