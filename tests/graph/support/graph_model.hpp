// An independent, flat description of a declared frame graph used by the reference code: which
// node uses which resource at which *position* in that resource's version chain (0 = the version
// created with the resource, k = the k-th write). Tests build it themselves (random_graph) and
// cross-check it against what FrameGraph recorded, so the reference never trusts the library.
#pragma once

#include "declaration.hpp"  // the library's own records (fgb_graph_internals)

#include <fgb/graph/frame_graph.hpp>

#include <span>

#include <cstdint>
#include <string>
#include <vector>

namespace fgb::graph::test {

using detail::Use;
using detail::VersionDecl;
inline std::span<const Use> usesOf(const FrameGraph& graph, uint32_t node) { return detail::Declared::uses(graph, node); }
inline const std::vector<VersionDecl>& versionsOf(const FrameGraph& graph) { return detail::Declared::versions(graph); }

inline constexpr int kNoPosition = -1;

struct ModelUse {
  uint32_t node = kInvalidIndex;
  uint32_t resource = kInvalidIndex;
  int readPos = kNoPosition;   // chain position read (reads only)
  int writePos = kNoPosition;  // chain position produced (writes only)
  Access access = Access::Sampled;
  StageMask shaderStages = kStageNone;
  [[nodiscard]] bool reads() const { return readPos != kNoPosition; }
  [[nodiscard]] bool writes() const { return writePos != kNoPosition; }
};

struct GraphModel {
  std::vector<std::string> nodeName;
  std::vector<NodeType> nodeType;
  std::vector<QueueClass> nodeClass;
  std::vector<bool> sideEffect;
  std::vector<std::string> resourceName;
  std::vector<ResourceKind> kind;
  std::vector<bool> imported;
  std::vector<ModelUse> uses;  // declaration order

  [[nodiscard]] uint32_t nodeCount() const { return static_cast<uint32_t>(nodeName.size()); }
  [[nodiscard]] uint32_t resourceCount() const { return static_cast<uint32_t>(resourceName.size()); }
};

// Derives the model from what a FrameGraph recorded (used for hand-written graphs; the random
// generator records its own model and compares it with this one).
GraphModel modelFromGraph(const FrameGraph& graph);

// Queue mapping used by every test: Q = 1 -> all on queue 0; Q = 2 -> graphics 0, compute and
// transfer 1; Q = 3 -> graphics/compute/transfer on 0/1/2. Families are distinct per queue.
std::array<uint32_t, kQueueClassCount> queueOfClassFor(uint32_t queueCount);

}  // namespace fgb::graph::test
