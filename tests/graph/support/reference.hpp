// Brute-force reference facts about a declared graph, computed from the GraphModel alone:
// version edges, cycles, culling by reverse reachability, the orderings every hazard demands, and
// longest-path levels. Deliberately simple (quadratic where that is clearer) and independent of
// the compiler's code.
#pragma once

#include "graph_model.hpp"

#include <fgb/graph/compiled_graph.hpp>

#include <cstdint>
#include <vector>

namespace fgb::graph::test {

// One ordering the declaration demands between two alive nodes because of one resource.
struct RequiredOrder {
  uint32_t before = kInvalidIndex;
  uint32_t after = kInvalidIndex;
  uint32_t resource = kInvalidIndex;
};

struct Reference {
  std::vector<Edge> declaredEdges;  // every node: RAW, WAR, WAW from versions, deduplicated
  std::vector<uint32_t> cycle;      // nodes on one cycle of declaredEdges; empty when acyclic
  std::vector<bool> alive;          // after culling (or all, without culling)
  std::vector<RequiredOrder> required;  // alive pairs that touch one resource, at least one writing
  std::vector<uint32_t> level;          // alive nodes: longest path over `required`
};

Reference computeReference(const GraphModel& model, bool cull);

// Transitive reachability on a small graph (BFS from every node).
class Reachability {
 public:
  Reachability(uint32_t nodeCount, const std::vector<Edge>& edges);
  // True when a path of at least one edge leads from `from` to `to`.
  [[nodiscard]] bool reaches(uint32_t from, uint32_t to) const { return reach_[from][to] != 0; }

 private:
  std::vector<std::vector<char>> reach_;
};

// Sort key of a use along its resource's version chain: the write of position k comes before every
// read of position k, which come before the write of k + 1.
int chainKey(const ModelUse& use);

}  // namespace fgb::graph::test
