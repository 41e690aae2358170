// Internal: state shared by the compiler stages (one file per stage, run in order by compiler.cpp).
#pragma once

#include <fgb/graph/compiler.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace fgb::graph::detail {

using QueueArray = std::array<uint32_t, kQueueClassCount>;

// Compressed adjacency: the neighbours of node i are items[start[i] .. start[i+1]).
struct Adjacency {
  std::vector<uint32_t> start;
  std::vector<uint32_t> items;
  [[nodiscard]] uint32_t begin(uint32_t node) const { return start[node]; }
  [[nodiscard]] uint32_t end(uint32_t node) const { return start[node + 1]; }
};

struct CompileState {
  CompileState(const FrameGraph& g, const CompileOptions& o, CompiledGraph& c)
      : graph(g), options(o), out(c), nodeCount(static_cast<uint32_t>(g.nodes().size())) {}

  const FrameGraph& graph;
  const CompileOptions& options;
  CompiledGraph& out;
  uint32_t nodeCount;

  std::vector<uint8_t> alive;        // per node
  bool anyCulled = false;
  std::vector<uint32_t> queueOf;     // per node: queue index
  Adjacency predecessors;            // per node: alive nodes it depends on (deduplicated)
  std::vector<uint32_t> sigma;       // per node: SSIS re-index σ(u) = order position + queue·V + 1
  std::vector<QueueArray> known;     // per node: per queue, the largest σ the node is ordered after
  std::vector<uint32_t> lastSigmaOnQueue;    // per resource × queue: largest σ of a user on that queue
  std::vector<StageMask> stagesOnQueue;      // per resource × queue: stages used on that queue
  std::vector<uint32_t> firstUser;           // per resource: node of the first alive use
};

// Readers of each version among the nodes selected by `alive`, in declaration order.
Adjacency collectVersionReaders(const FrameGraph& graph, const std::vector<uint8_t>& alive);

// Stages, in pipeline order.
void assignQueues(CompileState& state);
void detectCycles(const CompileState& state);          // over every declared node
// Throws GraphError naming a cycle among `left` (nodes Kahn's algorithm could not order).
[[noreturn]] void reportCycle(const CompileState& state, const Adjacency& preds, const std::vector<uint32_t>& left);
void cullNodes(CompileState& state);                    // fills alive + NodeInfo reasons
void buildDependencies(CompileState& state);            // RAW/WAR/WAW edges among alive nodes
void sortByLevel(CompileState& state);                  // levels + order
void pruneCrossQueueEdges(CompileState& state);         // SSIS → syncEdges, known
void placeSubmits(CompileState& state);                 // steps + submits + waits
void resolveResources(CompileState& state);             // dependent fields, requirements
void computeLifetimes(CompileState& state);
void placeTransients(CompileState& state);              // aliasing plan
void planBarriers(CompileState& state);

// Edges implied by resource versions among `alive` nodes (callback receives from, to).
template <typename EmitEdge>
void forEachVersionEdge(const FrameGraph& graph, const std::vector<uint8_t>& alive,
                        const std::vector<uint32_t>& queueOf, const Adjacency& readers, EmitEdge&& emit);

}  // namespace fgb::graph::detail

#include "version_edges.inl"
