// Internal: the declaration records a FrameGraph keeps, which only the compiler (and the
// library's own tests) read. The public view of a use is FrameGraph::accesses.
#pragma once

#include <fgb/graph/frame_graph.hpp>
#include <span>
#include <vector>

namespace fgb::graph::detail {

// One use of one resource version by one node.
struct Use {
  uint32_t resource = kInvalidIndex;
  uint32_t readVersion = kInvalidIndex;   // version read (valid if the access reads)
  uint32_t writeVersion = kInvalidIndex;  // version produced (valid if the access writes)
  StageMask shaderStages = kStageNone;    // as declared; 0: derive from the node type
  // accessInfo(access, node type, shaderStages), resolved at declaration.
  StageMask stages = kStageNone;
  AccessMask accessMask = kAccessNone;
  Access access = Access::Sampled;
  Layout layout = Layout::Undefined;
  [[nodiscard]] bool reads() const { return readVersion != kInvalidIndex; }
  [[nodiscard]] bool writes() const { return writeVersion != kInvalidIndex; }
};

// Versions are numbered across all resources, in declaration order.
struct VersionDecl {
  uint32_t resource = kInvalidIndex;
  uint32_t producer = kInvalidIndex;  // node that wrote it; kInvalidIndex for a resource's first version
  uint32_t previous = kInvalidIndex;  // version it was written over
};

// What a FrameGraph declared, beyond its public nodes() and resources().
struct Declared {
  static std::span<const Use> uses(const FrameGraph& graph, uint32_t node) {
    return {graph.uses_.data() + graph.useStart_[node], graph.useStart_[node + 1] - graph.useStart_[node]};
  }
  static const std::vector<Use>& allUses(const FrameGraph& graph) { return graph.uses_; }
  static const std::vector<VersionDecl>& versions(const FrameGraph& graph) { return graph.versions_; }
};

}  // namespace fgb::graph::detail
