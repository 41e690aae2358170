// The result of compiling a FrameGraph: everything a backend needs to run it, with no decisions
// left to make. Indices refer to FrameGraph::nodes()/resources() unless named otherwise.
#pragma once

#include <cstdint>
#include <fgb/graph/frame_graph.hpp>
#include <string>
#include <vector>

namespace fgb::graph {

struct Edge {
  uint32_t from = kInvalidIndex;  // runs first
  uint32_t to = kInvalidIndex;    // runs after `from`
  friend bool operator==(Edge, Edge) = default;
};

enum class CullReason : uint8_t {
  Alive,
  OutputsUnread,  // writes only resources nobody alive reads, none imported
  NoOutputs,      // declares no writes and no side effect
};

// The text saying why a node was culled is built on demand by cullDiagnostic() or CullDiagnostics
// (below): compiling builds none, as most culled nodes of a frame are never described to anyone.
struct NodeInfo {
  bool culled = false;
  CullReason reason = CullReason::Alive;
  uint32_t level = 0;                   // longest-path dependency level (alive nodes)
  uint32_t queue = 0;                   // queue index in [0, queueCount)
  uint32_t orderIndex = kInvalidIndex;  // position in CompiledGraph::order
  uint32_t step = kInvalidIndex;        // index into CompiledGraph::steps
  uint32_t submit = kInvalidIndex;      // index into CompiledGraph::submits
};

// A synchronisation barrier (image or buffer memory barrier, maybe an ownership transfer half).
struct Barrier {
  enum class Kind : uint8_t {
    Transition,  // same queue: execution + memory dependency, maybe a layout change
    Release,     // queue-family ownership release, recorded on the source queue
    Acquire,     // queue-family ownership acquire, recorded on the destination queue
  };
  Kind kind = Kind::Transition;
  uint32_t resource = kInvalidIndex;
  StageMask srcStages = kStageNone;
  AccessMask srcAccess = kAccessNone;
  StageMask dstStages = kStageNone;
  AccessMask dstAccess = kAccessNone;
  Layout oldLayout = Layout::Undefined;
  Layout newLayout = Layout::Undefined;
  uint32_t srcQueue = 0;  // queue indices; differ only for Release/Acquire
  uint32_t dstQueue = 0;
};

// A range [first, first + count) into CompiledGraph::barriers.
struct BarrierRange {
  uint32_t first = 0;
  uint32_t count = 0;
};

// One node in execution order with the barriers recorded around it.
struct Step {
  uint32_t node = kInvalidIndex;
  BarrierRange before;  // recorded before the node's job (transitions, acquires)
  BarrierRange after;   // recorded after it (releases to other queues, final import states)
};

struct SemaphoreWait {
  uint32_t queue = 0;
  uint64_t value = 0;  // per-frame timeline value; the backend adds frame * valuesPerFrame
  StageMask stages = kStageAllCommands;
};

// A vkQueueSubmit-sized batch: consecutive steps of one queue.
struct Submit {
  uint32_t queue = 0;
  uint32_t firstStep = 0;  // into CompiledGraph::steps
  uint32_t stepCount = 0;
  std::vector<SemaphoreWait> waits;
  uint64_t signalValue = 0;  // 1-based index of this submit on its queue
};

// Lifetimes are positions in CompiledGraph::order (the global topological order), not step
// indices: steps are grouped per queue and so are not one timeline when Q > 1.
struct Lifetime {
  uint32_t first = kInvalidIndex;  // order position of the first alive use
  uint32_t last = kInvalidIndex;   // order position of the last alive use
  // Across queues: memory is reused only once every queue that touched the resource has been
  // waited for by the new occupant's first user (see AliasingPlan), which is how the lifetime is
  // "extended until the consuming queue has waited".
  [[nodiscard]] bool used() const { return first != kInvalidIndex; }
};

struct MemoryRequirements {
  uint64_t size = 0;
  uint64_t alignment = 1;
  uint32_t memoryTypeBits = ~0u;
};

struct Placement {
  uint32_t heap = kInvalidIndex;  // into AliasingPlan::heaps; kInvalidIndex: imported or unused
  uint64_t offset = 0;
  uint64_t size = 0;
  // Stages (on the resource's first queue) of earlier occupants of this memory that the first-use
  // barrier must wait for, and their writes, which it makes available: an earlier occupant's write
  // still in a cache must not land on top of the new resource's data (write after write). Earlier
  // occupants on other queues are ordered by semaphores.
  StageMask aliasedAfterStages = kStageNone;
  AccessMask aliasedAfterWrites = kAccessNone;
};

struct Heap {
  ResourceKind kind = ResourceKind::Texture;  // buffers and images never share a heap (granularity)
  uint32_t memoryTypeBits = ~0u;              // every resource placed in it has exactly these bits
  uint64_t size = 0;
  uint64_t alignment = 1;
};

struct AliasingPlan {
  std::vector<Placement> placements;  // per resource
  std::vector<Heap> heaps;
  uint64_t peakBytesAliased = 0;    // sum of heap sizes
  uint64_t peakBytesUnaliased = 0;  // sum of every transient's aligned size
};

// Resolved descriptions (dependent fields replaced by values).
struct ResolvedResource {
  TextureDesc texture{};
  BufferDesc buffer{};
  MemoryRequirements requirements{};
};

struct CompiledGraph {
  uint32_t queueCount = 1;
  std::vector<NodeInfo> nodes;  // per declared node
  std::vector<uint32_t> order;  // alive nodes, topological, levels non-decreasing
  std::vector<Edge> edges;      // dependency edges between alive nodes (deduplicated)
  std::vector<Edge> syncEdges;  // G*: cross-queue edges kept after SSIS pruning
  std::vector<Step> steps;      // order, grouped by queue then submit (see submits)
  std::vector<Barrier> barriers;
  std::vector<Submit> submits;  // grouped by queue, ascending signal values per queue
  std::vector<uint32_t> submitsPerQueue;
  std::vector<ResolvedResource> resources;  // per declared resource
  std::vector<bool> resourceAlive;          // used by at least one alive node
  std::vector<Lifetime> lifetimes;          // per resource (positions in `order`)
  AliasingPlan aliasing;
};

// Why `node` was culled, for a person: "writes 'a' v3, 'b' v5, none imported; nothing reads them",
// "...; read only by culled nodes 'x', 'y'", or "declares no writes and no side effect". Empty for a
// node that was not culled. Indexes the whole graph (O(nodes + uses)): to describe many nodes,
// build one CullDiagnostics instead.
std::string cullDiagnostic(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t node);

// cullDiagnostic() for many nodes of one compiled graph (a Graphviz dump describes every culled
// node). The constructor indexes the readers of every version; then describe(node) costs only the
// uses of `node` and the readers of what it writes. Holds references to `graph` and `compiled`,
// which must outlive it and stay unchanged.
class CullDiagnostics {
 public:
  CullDiagnostics(const FrameGraph& graph, const CompiledGraph& compiled);

  // Exactly cullDiagnostic(graph, compiled, node).
  [[nodiscard]] std::string describe(uint32_t node) const;

 private:
  const FrameGraph& graph_;
  const CompiledGraph& compiled_;
  // The nodes that read version v are readers_[readerStart_[v], readerStart_[v + 1]), in
  // declaration order, once per use.
  std::vector<uint32_t> readerStart_;
  std::vector<uint32_t> readers_;
};

}  // namespace fgb::graph
