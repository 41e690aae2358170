// Declaration side of the frame graph (Frostbite's "setup" phase, the thesis' builder).
//
// A FrameGraph holds nodes (graphics/compute/transfer work with a job) and resources (imported or
// transient textures and buffers). Each write of a resource creates a new *version*; handles name a
// version, so a stale handle can be detected and ordering falls out of version numbers:
//   RAW: producer(v) -> every reader of v
//   WAR: every reader of v -> the writer that produces v+1
//   WAW: producer(v) -> the writer that produces v+1
// Nothing here knows Vulkan: jobs receive an opaque JobContext that the backend subclasses.
#pragma once

#include <array>
#include <cstdint>
#include <fgb/graph/format.hpp>
#include <fgb/graph/types.hpp>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fgb::graph {

// Thrown for declaration and compile errors; the message names the nodes and resources involved.
class GraphError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ResourceKind : uint8_t { Texture, Buffer };

// Handles name one version of one resource. Default-constructed handles are invalid.
template <ResourceKind Kind>
struct Handle {
  uint32_t version = kInvalidIndex;
  [[nodiscard]] bool valid() const { return version != kInvalidIndex; }
  friend bool operator==(Handle, Handle) = default;
};
using TextureHandle = Handle<ResourceKind::Texture>;
using BufferHandle = Handle<ResourceKind::Buffer>;

struct Extent {
  uint32_t width = 1;
  uint32_t height = 1;
  uint32_t depth = 1;
};

struct TextureDesc {
  Format format = Format::Undefined;
  Extent extent{};
  uint32_t mipLevels = 1;
  uint32_t layers = 1;
  uint32_t samples = 1;
  // Dependent field: when valid, extent = extent of this version's resource >> extentShift
  // (at least 1), resolved at compile time. "Same size as the colour target", "half of it", ...
  TextureHandle extentFrom{};
  uint32_t extentShift = 0;
};

struct BufferDesc {
  uint64_t size = 0;
  // Dependent field: when valid, size = that buffer's size (resolved at compile time).
  BufferHandle sizeFrom{};
};

// Opaque identity of an imported resource in the backend (e.g. an index into its resource table).
struct ExternalResource {
  uint64_t id = 0;
};

// State an imported resource is in before the graph runs, and must be left in afterwards.
struct ImportState {
  StageMask stages = kStageNone;
  AccessMask access = kAccessNone;
  Layout layout = Layout::Undefined;
  QueueClass queue = QueueClass::Graphics;
};

enum class LoadOp : uint8_t { Load, Clear, DontCare };
enum class StoreOp : uint8_t { Store, DontCare };

struct ClearValue {
  std::array<float, 4> color{0, 0, 0, 0};
  float depth = 1.0f;
  uint32_t stencil = 0;
};

struct ColorAttachment {
  TextureHandle target;         // the version written by the node
  TextureHandle resolveTarget;  // optional multisample resolve output (version written)
  LoadOp load = LoadOp::Clear;
  StoreOp store = StoreOp::Store;
  ClearValue clear{};
};

struct DepthAttachment {
  TextureHandle target;  // the version used (written unless readOnly)
  LoadOp load = LoadOp::Clear;
  StoreOp store = StoreOp::Store;
  ClearValue clear{};
  bool readOnly = false;
};

// One resource a node uses, and how (FrameGraph::accesses): what a backend or a feature needs to
// choose usage flags, bind resources or follow versions (the compiler's own record is private).
struct ResourceAccess {
  uint32_t resource = kInvalidIndex;
  Access access = Access::Sampled;
  uint32_t readVersion = kInvalidIndex;   // the version read, if the access reads
  uint32_t writeVersion = kInvalidIndex;  // the version created, if the access writes
};

class JobContext {
 public:
  virtual ~JobContext() = default;
};
using Job = std::function<void(JobContext&)>;
// What a job's recording depends on (NodeBuilder::recordingDependsOn): a hash of every host value
// the job reads while recording. A backend may keep a node's recorded commands and submit them
// again while this key (and what the backend itself knows of the node) is unchanged.
using RecordingKey = std::function<uint64_t()>;
// Folds `value` into `hash`, for recording keys (order matters: (a, b) and (b, a) differ).
constexpr uint64_t hashCombine(uint64_t hash, uint64_t value) {
  return (hash ^ (value + 0x9e3779b97f4a7c15ull + (hash << 6) + (hash >> 2))) * 0xff51afd7ed558ccdull;
}

struct ResourceDecl {
  std::string name;
  ResourceKind kind = ResourceKind::Texture;
  bool imported = false;
  TextureDesc texture{};
  BufferDesc buffer{};
  ExternalResource external{};
  ImportState initialState{};
  ImportState finalState{};
  uint32_t firstVersion = kInvalidIndex;   // the version created with the resource
  uint32_t latestVersion = kInvalidIndex;  // newest version so far (writes must start from it)
};

// The attachments of a graphics node (FrameGraph::attachments).
struct NodeAttachments {
  std::vector<ColorAttachment> color;
  DepthAttachment depth{};  // target invalid if none
};

struct NodeDecl {
  std::string name;
  NodeType type = NodeType::Graphics;
  QueueClass queue = QueueClass::Graphics;
  bool sideEffect = false;
};

class FrameGraph;
namespace detail {
struct Use;
struct VersionDecl;
struct Declared;
}  // namespace detail

// Fluent declaration of one node. Obtained from FrameGraph::addNode; valid until the next addNode.
class NodeBuilder {
 public:
  NodeBuilder(FrameGraph& graph, uint32_t node) : graph_(&graph), node_(node) {}

  TextureHandle read(TextureHandle texture, Access access = Access::Sampled, StageMask stages = kStageNone);
  BufferHandle read(BufferHandle buffer, Access access, StageMask stages = kStageNone);
  // Write: `texture` must be the latest version; returns the new version.
  TextureHandle write(TextureHandle texture, Access access, StageMask stages = kStageNone);
  BufferHandle write(BufferHandle buffer, Access access, StageMask stages = kStageNone);

  // Attachments of a graphics node (thesis: AddColorTarget / SetDepthStencil). Return new versions.
  TextureHandle addColorTarget(TextureHandle target, LoadOp load = LoadOp::Clear, ClearValue clear = {});
  // Colour target with a resolve: returns the new version of `resolveTarget`.
  TextureHandle addColorTargetWithResolve(TextureHandle target, TextureHandle resolveTarget,
                                          TextureHandle* newTargetVersion = nullptr, LoadOp load = LoadOp::Clear,
                                          ClearValue clear = {});
  TextureHandle setDepthStencil(TextureHandle target, LoadOp load = LoadOp::Clear, ClearValue clear = {});
  void setDepthStencilReadOnly(TextureHandle target);

  // A side-effect node is never culled and keeps everything it reads alive (readbacks, debug dumps).
  NodeBuilder& sideEffect();
  NodeBuilder& setJob(Job job);
  // The job's recording depends only on `key()` (evaluated before each execution) and on what the
  // graph itself fixes (resources, extents): its commands may be recorded once and reused while
  // the key stays equal. Without it the job records every execution (the safe default).
  NodeBuilder& recordingDependsOn(RecordingKey key);
  // The job reads no host state that changes after declaration (a constant key).
  NodeBuilder& recordingFixed() {
    return recordingDependsOn([] { return uint64_t{0}; });
  }

  [[nodiscard]] uint32_t index() const { return node_; }

 private:
  FrameGraph* graph_;
  uint32_t node_;
};

class FrameGraph {
 public:
  // Defined where the declaration records (detail::Use, detail::VersionDecl) are complete.
  FrameGraph();
  ~FrameGraph();
  FrameGraph(const FrameGraph& other);
  FrameGraph& operator=(const FrameGraph& other);
  FrameGraph(FrameGraph&& other) noexcept;
  FrameGraph& operator=(FrameGraph&& other) noexcept;

  TextureHandle importTexture(std::string_view name, const TextureDesc& desc, ExternalResource external,
                              ImportState initial, ImportState final);
  BufferHandle importBuffer(std::string_view name, const BufferDesc& desc, ExternalResource external,
                            ImportState initial, ImportState final);
  TextureHandle createTexture(std::string_view name, const TextureDesc& desc);
  BufferHandle createBuffer(std::string_view name, const BufferDesc& desc);

  NodeBuilder addNode(std::string_view name, NodeType type);
  NodeBuilder addNode(std::string_view name, NodeType type, QueueClass queue);

  [[nodiscard]] const std::vector<NodeDecl>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<ResourceDecl>& resources() const { return resources_; }
  // The resources `node` uses and how, in declaration order.
  [[nodiscard]] std::vector<ResourceAccess> accesses(uint32_t node) const;
  [[nodiscard]] uint32_t resourceOf(TextureHandle h) const { return resourceOf(h.version, "texture"); }
  [[nodiscard]] uint32_t resourceOf(BufferHandle h) const { return resourceOf(h.version, "buffer"); }
  // No colour target and an invalid depth target for a node that declared none.
  [[nodiscard]] const NodeAttachments& attachments(uint32_t node) const { return attachments_[node]; }
  // Moves the jobs out (indexed by node; empty where none was set): the backend keeps them when it
  // builds an executable graph.
  std::vector<Job> takeJobs() { return std::exchange(jobs_, std::vector<Job>(nodes_.size())); }
  // Likewise the recording keys (empty where the node declared none).
  std::vector<RecordingKey> takeRecordingKeys() {
    return std::exchange(recordingKeys_, std::vector<RecordingKey>(nodes_.size()));
  }

 private:
  friend class NodeBuilder;
  friend struct detail::Declared;
  uint32_t addResource(ResourceDecl decl);  // returns its first version
  void checkDependentField(const ResourceDecl& decl) const;
  const ResourceDecl& checkUse(uint32_t node, uint32_t version, ResourceKind kind, Access access) const;
  uint32_t addUse(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages, bool write);
  uint32_t addAttachmentUse(uint32_t node, uint32_t version, Access access);
  uint32_t resourceOf(uint32_t version, const char* kind) const;

  std::vector<NodeDecl> nodes_;
  std::vector<ResourceDecl> resources_;
  std::vector<detail::VersionDecl> versions_;
  // Node n's uses are uses_[useStart_[n], useStart_[n + 1]): one array for every node's uses.
  std::vector<detail::Use> uses_;
  std::vector<uint32_t> useStart_;
  std::vector<NodeAttachments> attachments_;  // by node
  std::vector<Job> jobs_;                     // by node; empty where none was set
  std::vector<RecordingKey> recordingKeys_;   // by node; empty where none was declared
};

}  // namespace fgb::graph
