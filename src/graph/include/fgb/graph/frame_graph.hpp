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

#include <fgb/graph/format.hpp>
#include <fgb/graph/types.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::graph {

// Thrown for declaration and compile errors; the message names the nodes and resources involved.
class GraphError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Handles name one version of one resource. Default-constructed handles are invalid.
struct TextureHandle {
  uint32_t version = kInvalidIndex;
  [[nodiscard]] bool valid() const { return version != kInvalidIndex; }
  friend bool operator==(TextureHandle, TextureHandle) = default;
};
struct BufferHandle {
  uint32_t version = kInvalidIndex;
  [[nodiscard]] bool valid() const { return version != kInvalidIndex; }
  friend bool operator==(BufferHandle, BufferHandle) = default;
};

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
  TextureHandle target;        // the version written by the node
  TextureHandle resolveTarget; // optional multisample resolve output (version written)
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

// One use of one resource version by one node.
struct Use {
  uint32_t resource = kInvalidIndex;
  uint32_t readVersion = kInvalidIndex;   // version read (valid if the access reads)
  uint32_t writeVersion = kInvalidIndex;  // version produced (valid if the access writes)
  // The node that wrote readVersion (kInvalidIndex if none: no read, or an import's first version),
  // noted at declaration so that the compiler need not look each read's version up.
  uint32_t readProducer = kInvalidIndex;
  StageMask shaderStages = kStageNone;    // as declared; 0: derive from node type
  // accessInfo(access, node type, shaderStages), computed once at declaration.
  StageMask stages = kStageNone;
  AccessMask accessMask = kAccessNone;
  Access access = Access::Sampled;
  Layout layout = Layout::Undefined;
};

class JobContext {
 public:
  virtual ~JobContext() = default;
};
using Job = std::function<void(JobContext&)>;

enum class ResourceKind : uint8_t { Texture, Buffer };

struct ResourceDecl {
  std::string_view name;  // held by the FrameGraph, NUL-terminated (see NameStore)
  ResourceKind kind = ResourceKind::Texture;
  bool imported = false;
  TextureDesc texture{};
  BufferDesc buffer{};
  ExternalResource external{};
  ImportState initialState{};
  ImportState finalState{};
  uint32_t firstVersion = kInvalidIndex;   // the version created with the resource
  uint32_t latestVersion = kInvalidIndex;  // newest version so far (writes must start from it)
  uint32_t lastUser = kInvalidIndex;       // the node that used it last, so far
};

struct VersionDecl {
  uint32_t resource = kInvalidIndex;
  uint32_t producer = kInvalidIndex;  // node that wrote it; kInvalidIndex for a first version
  uint32_t previous = kInvalidIndex;  // version it was written over
};

// The attachments of a graphics node (FrameGraph::attachments).
struct NodeAttachments {
  std::vector<ColorAttachment> color;
  DepthAttachment depth{};  // target invalid if none
};

struct NodeDecl {
  std::string_view name;  // held by the FrameGraph, NUL-terminated (see NameStore)
  NodeType type = NodeType::Graphics;
  QueueClass queue = QueueClass::Graphics;
  bool sideEffect = false;
  // The rest of a node lives in FrameGraph, apart from NodeDecl, which every node declared pays
  // for: its uses in one flat array for all nodes (FrameGraph::uses, allUses: declaring 10,000
  // nodes must not cost 10,000 allocations), its attachments (FrameGraph::attachments: most nodes
  // have none) and its job (FrameGraph::takeJobs: the compiler never looks at it).
};

class FrameGraph;

// The names of a graph's nodes and resources, copied into blocks that never move, so that a
// NodeDecl or ResourceDecl holds a view of its name. Names are the only part of a declaration that
// would otherwise own memory: a std::string in each made every declaration pay for constructing
// it, and every destroyed graph for visiting each of them (about 3 % of declaring and compiling
// a 10,000-node graph).
// Blocks come from, and go back to, the per-thread pool that FrameGraph's arrays use.
class NameStore {
 public:
  NameStore() = default;
  ~NameStore();
  NameStore(const NameStore&) = delete;  // views would point into the original: FrameGraph re-adds
  NameStore& operator=(const NameStore&) = delete;
  // Blocks move with their storage, so views stay valid; the moved-from store is empty.
  NameStore(NameStore&& other) noexcept;
  NameStore& operator=(NameStore&& other) noexcept;

  // A view of a copy of `name`, valid as long as this store (or the store it is moved into). The
  // copy ends in a NUL (view.data() is a C string, as Vulkan's debug labels want).
  std::string_view add(std::string_view name) {
    if (name.empty()) return {"", 0};
    const size_t bytes = name.size() + 1;
    if (bytes > free_) newBlock(bytes);
    char* const at = next_;
    copyName(at, name);
    at[name.size()] = '\0';
    next_ += bytes;
    free_ -= bytes;
    return {at, name.size()};
  }

 private:
  // Names are mostly short ("gbuffer", "node1234"): up to 16 bytes are copied with two
  // overlapping loads and stores of 8 (or 4, or 1) bytes each, with no call to memcpy.
  static void copyName(char* to, std::string_view name) {
    const char* from = name.data();
    const size_t n = name.size();
    if (n > 16) {
      name.copy(to, n);
    } else if (n >= 8) {
      copyBytes<8>(to, from);
      copyBytes<8>(to + n - 8, from + n - 8);
    } else if (n >= 4) {
      copyBytes<4>(to, from);
      copyBytes<4>(to + n - 4, from + n - 4);
    } else {
      for (size_t i = 0; i < n; ++i) to[i] = from[i];
    }
  }
  template <size_t Bytes>
  static void copyBytes(char* to, const char* from) {
    char chunk[Bytes];
    std::memcpy(chunk, from, Bytes);  // one unaligned load
    std::memcpy(to, chunk, Bytes);    // one unaligned store
  }
  void newBlock(size_t atLeast);
  void release() noexcept;

  std::vector<std::vector<char>> blocks_;  // each filled up to its capacity, never beyond
  char* next_ = nullptr;
  size_t free_ = 0;
};

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
                                          TextureHandle* newTargetVersion = nullptr,
                                          LoadOp load = LoadOp::Clear, ClearValue clear = {});
  TextureHandle setDepthStencil(TextureHandle target, LoadOp load = LoadOp::Clear, ClearValue clear = {});
  void setDepthStencilReadOnly(TextureHandle target);

  // A side-effect node is never culled and keeps everything it reads alive (readbacks, debug dumps).
  NodeBuilder& sideEffect();
  NodeBuilder& setJob(Job job);

  [[nodiscard]] uint32_t index() const { return node_; }

 private:
  FrameGraph* graph_;
  uint32_t node_;
};

class FrameGraph {
 public:
  // A graph is declared every frame: its arrays come from, and go back to, a per-thread pool, so
  // a frame reuses the previous frame's storage instead of allocating (and page-faulting) anew.
  FrameGraph();
  ~FrameGraph();
  // A copy holds copies of the names (see NameStore).
  FrameGraph(const FrameGraph& other);
  FrameGraph& operator=(const FrameGraph& other);
  FrameGraph(FrameGraph&&) noexcept = default;
  FrameGraph& operator=(FrameGraph&&) noexcept = default;

  TextureHandle importTexture(std::string_view name, const TextureDesc& desc, ExternalResource external,
                              ImportState initial, ImportState final);
  BufferHandle importBuffer(std::string_view name, const BufferDesc& desc, ExternalResource external,
                            ImportState initial, ImportState final);
  TextureHandle createTexture(std::string_view name, const TextureDesc& desc);
  BufferHandle createBuffer(std::string_view name, const BufferDesc& desc);

  NodeBuilder addNode(std::string_view name, NodeType type);
  NodeBuilder addNode(std::string_view name, NodeType type, QueueClass queue);

  void reserve(size_t nodes, size_t resources);

  [[nodiscard]] const std::vector<NodeDecl>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<ResourceDecl>& resources() const { return resources_; }
  [[nodiscard]] const std::vector<VersionDecl>& versions() const { return versions_; }
  [[nodiscard]] std::span<const Use> uses(uint32_t node) const {
    return {allUses_.data() + useStart_[node], useStart_[node + 1] - useStart_[node]};
  }
  [[nodiscard]] const std::vector<Use>& allUses() const { return allUses_; }
  // True when some node read a version after another node had already written over it (an
  // "old-version" read). Only such a read orders a node before an earlier-declared one (WAR), so
  // without one the declaration order is already a topological order of every dependency.
  [[nodiscard]] bool readsOldVersions() const { return readsOldVersions_; }
  // True when some node used one resource more than once (e.g. read it and resolved into it):
  // without one, the compiler takes each use as its node's only use of the resource.
  [[nodiscard]] bool someNodeUsesAResourceTwice() const { return usesAResourceTwice_; }
  [[nodiscard]] uint32_t resourceOf(TextureHandle h) const { return versionAt(h.version, "texture").resource; }
  [[nodiscard]] uint32_t resourceOf(BufferHandle h) const { return versionAt(h.version, "buffer").resource; }
  // No colour target and an invalid depth target for a node that declared none.
  [[nodiscard]] const NodeAttachments& attachments(uint32_t node) const;
  // Moves the jobs out (indexed by node; empty where none was set): the backend keeps them when it
  // builds an executable graph.
  std::vector<Job> takeJobs();

 private:
  friend class NodeBuilder;
  // The attachments of `node`, the newest node, created on first use.
  NodeAttachments& newestNodeAttachments(uint32_t node);
  ResourceDecl& addResource(std::string_view name, ResourceKind kind, bool imported, const TextureDesc& texture,
                            const BufferDesc& buffer);
  struct UseContext;
  UseContext beginUse(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages);
  void recordUse(const UseContext& use, uint32_t readVersion, uint32_t readProducer, uint32_t writeVersion,
                 Access access, StageMask stages);
  uint32_t checkRead(const UseContext& use, uint32_t version);
  uint32_t addRead(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages);
  uint32_t addWrite(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages);
  uint32_t addUse(uint32_t node, uint32_t version, Access access);  // a texture attachment's use
  void noteOldVersionRead(uint32_t node, uint32_t version, uint32_t latest);
  const VersionDecl& versionAt(uint32_t version, std::string_view what) const;

  std::vector<NodeDecl> nodes_;
  std::vector<ResourceDecl> resources_;
  std::vector<VersionDecl> versions_;
  std::vector<Use> allUses_;
  // Node n's uses are allUses_[useStart_[n], useStart_[n + 1]). Kept apart from NodeDecl, which
  // is large: the compiler walks uses node by node and should not touch the rest of a node.
  std::vector<uint32_t> useStart_;
  // Only the nodes that declared attachments, in node order (so a lookup is a binary search).
  struct AttachmentsOf {
    uint32_t node;
    NodeAttachments attachments;
  };
  std::vector<AttachmentsOf> attachments_;
  // Job of node n at jobs_[n]; nodes from jobs_.size() on have none.
  std::vector<Job> jobs_;
  bool readsOldVersions_ = false;
  bool usesAResourceTwice_ = false;
  NameStore names_;
};

}  // namespace fgb::graph
