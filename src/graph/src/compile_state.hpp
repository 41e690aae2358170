// Internal: state shared by the compiler stages (one file per stage, run in order by compiler.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <fgb/graph/compiler.hpp>
#include <vector>

#include "declaration.hpp"

namespace fgb::graph::detail {

// One value per queue. compile() accepts at most kQueueClassCount queues; the stages loop over
// the queueCount in use, and entries past it stay 0.
using QueueArray = std::array<uint32_t, kQueueClassCount>;

// The readers of each version among all declared nodes: readers[start[v] .. start[v + 1]) read
// version v, in declaration order, a node once per use of it. Used by the dependency stage (for its
// version edges) and by CullDiagnostics.
void indexVersionReaders(const FrameGraph& graph, std::vector<uint32_t>& start, std::vector<uint32_t>& readers);

struct CompileState {
  CompileState(const FrameGraph& g, const CompileOptions& o, CompiledGraph& c)
      : graph(g),
        options(o),
        out(c),
        nodeCount(static_cast<uint32_t>(g.nodes().size())),
        resourceCount(static_cast<uint32_t>(g.resources().size())),
        queueCount(o.queueCount) {}

  [[nodiscard]] std::span<const Use> uses(uint32_t node) const { return Declared::uses(graph, node); }
  [[nodiscard]] const std::vector<VersionDecl>& versions() const { return Declared::versions(graph); }
  [[nodiscard]] const ResourceDecl& resource(uint32_t r) const { return graph.resources()[r]; }
  [[nodiscard]] bool isImported(uint32_t r) const { return resource(r).imported; }
  [[nodiscard]] bool isTexture(uint32_t r) const { return resource(r).kind == ResourceKind::Texture; }

  const FrameGraph& graph;
  const CompileOptions& options;
  CompiledGraph& out;
  uint32_t nodeCount;
  uint32_t resourceCount;
  uint32_t queueCount;

  std::vector<uint8_t> alive;       // per node (culling)
  std::vector<uint32_t> aliveUses;  // per resource: how many uses alive nodes make of it (culling)
  std::vector<uint32_t> queueOf;    // per node: queue index (culling)
  // Per node: its dependencies are out.edges[edgeStart[n] .. edgeEnd[n]) (the edges into n).
  std::vector<uint32_t> edgeStart;
  std::vector<uint32_t> edgeEnd;
  uint32_t maxLevel = 0;  // the largest NodeInfo::level (dependencies)
  // With several queues (SSIS), per node: σ(u) = order position + queue·V + 1 (V alive nodes)
  // numbers each queue's nodes contiguously, so comparing σ on one queue compares order; `known`
  // holds, per queue, the largest σ that u is ordered after (0: none).
  std::vector<uint32_t> sigma;
  std::vector<QueueArray> known;
};

// Stages, in pipeline order.
void resolveResources(CompileState& state);      // out.resources: dependent fields resolved
void cullNodes(CompileState& state);             // queueOf, alive + NodeInfo reasons, aliveUses
void buildDependencies(CompileState& state);     // out.edges (RAW/WAR/WAW, reader chains), NodeInfo levels; cycles
void sortByLevel(CompileState& state);           // out.order, NodeInfo order positions
void pruneCrossQueueEdges(CompileState& state);  // SSIS: out.syncEdges, sigma, known
void placeSubmits(CompileState& state);          // out.steps, out.submits and their waits
// Lifetimes, memory requirements, aliasing plan and barriers, in one walk over the order.
void placeAndPlanBarriers(CompileState& state);

}  // namespace fgb::graph::detail
