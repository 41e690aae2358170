#include <fgb/graph/frame_graph.hpp>

#include "access_table.hpp"
#include "vector_pool.hpp"

#include <algorithm>
#include <string>
#include <utility>

namespace fgb::graph {
namespace {

std::string quoted(std::string_view name) { return "'" + std::string(name) + "'"; }

[[noreturn, gnu::cold, gnu::noinline]] void throwUnknownNodeKind(std::string_view name, NodeType type,
                                                                 QueueClass queue) {
  throw GraphError("node " + quoted(name) + ": unknown node type " + std::to_string(static_cast<int>(type)) +
                   " or queue class " + std::to_string(static_cast<int>(queue)));
}

// Doubles the capacity of `array`: out of line, so that an append inlined into a declaration (below)
// keeps no registers and code for reallocating.
template <typename T>
[[gnu::cold, gnu::noinline]] void grow(std::vector<T>& array) {
  array.reserve(std::max<size_t>(64, array.capacity() * 2));
}

// array.emplace_back(args...), with the reallocation kept out of line (see grow).
template <typename T, typename... Args>
[[gnu::always_inline]] inline T& append(std::vector<T>& array, Args&&... args) {
  if (array.size() == array.capacity()) grow(array);
  if (array.size() == array.capacity()) __builtin_unreachable();  // tells the compiler emplace_back won't grow
  return array.emplace_back(std::forward<Args>(args)...);
}

}  // namespace

// ---- NameStore --------------------------------------------------------------------------------

namespace {
// Room for about 8,000 short names a block: a 10,000-node graph needs three.
constexpr size_t kNameBlockBytes = 64 * 1024;
}  // namespace

NameStore::~NameStore() { release(); }

NameStore::NameStore(NameStore&& other) noexcept
    : blocks_(std::move(other.blocks_)), next_(std::exchange(other.next_, nullptr)),
      free_(std::exchange(other.free_, 0)) {
  other.blocks_.clear();
}

NameStore& NameStore::operator=(NameStore&& other) noexcept {
  if (this == &other) return *this;
  release();
  blocks_ = std::move(other.blocks_);
  other.blocks_.clear();
  next_ = std::exchange(other.next_, nullptr);
  free_ = std::exchange(other.free_, 0);
  return *this;
}

void NameStore::newBlock(size_t atLeast) {
  std::vector<char> block;
  detail::VectorPool<char>::take(block);
  block.reserve(std::max(atLeast, kNameBlockBytes));
  // Filled through next_, up to the capacity: the vector's size stays 0 and nothing reallocates.
  next_ = block.data();
  free_ = block.capacity();
  blocks_.push_back(std::move(block));
}

void NameStore::release() noexcept {
  for (std::vector<char>& block : blocks_) detail::VectorPool<char>::give(block);
  blocks_.clear();
  next_ = nullptr;
  free_ = 0;
}

// ---- FrameGraph -------------------------------------------------------------------------------

FrameGraph::FrameGraph() {
  detail::VectorPool<NodeDecl>::take(nodes_);
  detail::VectorPool<ResourceDecl>::take(resources_);
  detail::VectorPool<VersionDecl>::take(versions_);
  detail::VectorPool<Use>::take(allUses_);
  detail::VectorPool<uint32_t>::take(useStart_);
  detail::VectorPool<AttachmentsOf>::take(attachments_);
  detail::VectorPool<Job>::take(jobs_);
  useStart_.push_back(0);  // node 0's first use
}

FrameGraph::~FrameGraph() {
  detail::VectorPool<NodeDecl>::give(nodes_);
  detail::VectorPool<ResourceDecl>::give(resources_);
  detail::VectorPool<VersionDecl>::give(versions_);
  detail::VectorPool<Use>::give(allUses_);
  detail::VectorPool<uint32_t>::give(useStart_);
  detail::VectorPool<AttachmentsOf>::give(attachments_);
  detail::VectorPool<Job>::give(jobs_);
}

FrameGraph::FrameGraph(const FrameGraph& other)
    : nodes_(other.nodes_),
      resources_(other.resources_),
      versions_(other.versions_),
      allUses_(other.allUses_),
      useStart_(other.useStart_),
      attachments_(other.attachments_),
      jobs_(other.jobs_),
      readsOldVersions_(other.readsOldVersions_),
      usesAResourceTwice_(other.usesAResourceTwice_) {
  for (NodeDecl& node : nodes_) node.name = names_.add(node.name);  // still the original's view
  for (ResourceDecl& resource : resources_) resource.name = names_.add(resource.name);
}

FrameGraph& FrameGraph::operator=(const FrameGraph& other) {
  if (this != &other) *this = FrameGraph(other);
  return *this;
}

void FrameGraph::reserve(size_t nodes, size_t resources) {
  nodes_.reserve(nodes);
  resources_.reserve(resources);
  versions_.reserve(resources + nodes);
  allUses_.reserve(nodes * 3);
  useStart_.reserve(nodes + 1);
}

const NodeAttachments& FrameGraph::attachments(uint32_t node) const {
  const auto found = std::lower_bound(attachments_.begin(), attachments_.end(), node,
                                      [](const AttachmentsOf& entry, uint32_t n) { return entry.node < n; });
  static const NodeAttachments kNone{};
  return found != attachments_.end() && found->node == node ? found->attachments : kNone;
}

NodeAttachments& FrameGraph::newestNodeAttachments(uint32_t node) {
  if (attachments_.empty() || attachments_.back().node != node) attachments_.push_back({node, {}});
  return attachments_.back().attachments;
}

std::vector<Job> FrameGraph::takeJobs() {
  std::vector<Job> jobs = std::move(jobs_);
  jobs.resize(nodes_.size());
  jobs_.clear();
  return jobs;
}

const VersionDecl& FrameGraph::versionAt(uint32_t version, std::string_view what) const {
  if (version >= versions_.size()) {
    throw GraphError("unknown " + std::string(what) + " version " +
                     (version == kInvalidIndex ? std::string("(invalid handle)") : std::to_string(version)));
  }
  return versions_[version];
}

// Inlined into its callers (createTexture and the like), for the same reason as addUse (below).
[[gnu::always_inline]] inline ResourceDecl& FrameGraph::addResource(std::string_view name, ResourceKind kind,
                                                                    bool imported, const TextureDesc& texture,
                                                                    const BufferDesc& buffer) {
  const auto resource = static_cast<uint32_t>(resources_.size());
  const auto version = static_cast<uint32_t>(versions_.size());
  versions_.emplace_back(resource, kInvalidIndex, kInvalidIndex);  // a first version: no producer, no previous
  // Every member given: value-initialising a struct this large first clears it with `rep stos`,
  // which costs several times more per declaration than storing each member once.
  return resources_.emplace_back(names_.add(name), kind, imported, texture, buffer, ExternalResource{},
                                 ImportState{}, ImportState{}, version, version);
}

TextureHandle FrameGraph::importTexture(std::string_view name, const TextureDesc& desc, ExternalResource external,
                                        ImportState initial, ImportState final) {
  if (desc.extentFrom.valid()) {
    const auto& source = versionAt(desc.extentFrom.version, "texture");
    if (resources_[source.resource].kind != ResourceKind::Texture) {
      throw GraphError("texture " + quoted(name) + ": extentFrom names buffer " +
                       quoted(resources_[source.resource].name));
    }
  }
  ResourceDecl& decl = addResource(name, ResourceKind::Texture, true, desc, {});
  decl.external = external;
  decl.initialState = initial;
  decl.finalState = final;
  return {decl.firstVersion};
}

BufferHandle FrameGraph::importBuffer(std::string_view name, const BufferDesc& desc, ExternalResource external,
                                      ImportState initial, ImportState final) {
  ResourceDecl& decl = addResource(name, ResourceKind::Buffer, true, {}, desc);
  decl.external = external;
  decl.initialState = initial;
  decl.finalState = final;
  return {decl.firstVersion};
}

TextureHandle FrameGraph::createTexture(std::string_view name, const TextureDesc& desc) {
  if (desc.extentFrom.valid()) {
    if (desc.extentFrom.version >= versions_.size()) {
      throw GraphError("texture " + quoted(name) + ": dependent field extentFrom names unknown resource version " +
                       std::to_string(desc.extentFrom.version));
    }
    const auto& source = versions_[desc.extentFrom.version];
    if (resources_[source.resource].kind != ResourceKind::Texture) {
      throw GraphError("texture " + quoted(name) + ": dependent field extentFrom names buffer " +
                       quoted(resources_[source.resource].name) + ", not a texture");
    }
  } else if (desc.format == Format::Undefined) {
    throw GraphError("texture " + quoted(name) + ": format is UNDEFINED");
  }
  return {addResource(name, ResourceKind::Texture, false, desc, {}).firstVersion};
}

BufferHandle FrameGraph::createBuffer(std::string_view name, const BufferDesc& desc) {
  if (desc.sizeFrom.valid()) {
    if (desc.sizeFrom.version >= versions_.size()) {
      throw GraphError("buffer " + quoted(name) + ": dependent field sizeFrom names unknown resource version " +
                       std::to_string(desc.sizeFrom.version));
    }
    const auto& source = versions_[desc.sizeFrom.version];
    if (resources_[source.resource].kind != ResourceKind::Buffer) {
      throw GraphError("buffer " + quoted(name) + ": dependent field sizeFrom names texture " +
                       quoted(resources_[source.resource].name) + ", not a buffer");
    }
  } else if (desc.size == 0) {
    throw GraphError("buffer " + quoted(name) + ": size is 0");
  }
  return {addResource(name, ResourceKind::Buffer, false, {}, desc).firstVersion};
}

NodeBuilder FrameGraph::addNode(std::string_view name, NodeType type) {
  return addNode(name, type, defaultQueue(type));
}

NodeBuilder FrameGraph::addNode(std::string_view name, NodeType type, QueueClass queue) {
  // Checked once here, so that every use can index tables by the node's type (and the compiler by its queue).
  if (static_cast<size_t>(type) >= detail::kShaderStagesOfType.size() ||
      static_cast<size_t>(queue) >= kQueueClassCount) {
    throwUnknownNodeKind(name, type, queue);
  }
  const auto node = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back(names_.add(name), type, queue, false);
  if (useStart_.empty()) useStart_.push_back(0);  // a moved-from graph being reused
  useStart_.push_back(useStart_.back());          // the new node's end, moved on by each of its uses
  return NodeBuilder(*this, node);
}

namespace {

// Declaration errors, kept out of line: building their messages in addUse itself would make every
// use pay for the stack frame of those strings.
[[noreturn, gnu::cold, gnu::noinline]] void throwUseError(const NodeDecl& node, std::string_view what) {
  throw GraphError("node " + quoted(node.name) + std::string(what));
}

[[noreturn, gnu::cold, gnu::noinline]] void throwUnknownVersion(const NodeDecl& node, ResourceKind kind,
                                                                uint32_t version) {
  throwUseError(node, " uses an unknown " + std::string(kind == ResourceKind::Texture ? "texture" : "buffer") +
                          " version " +
                          (version == kInvalidIndex ? std::string("(invalid handle)") : std::to_string(version)));
}

[[noreturn, gnu::cold, gnu::noinline]] void throwWrongKind(const NodeDecl& node, const ResourceDecl& res,
                                                           ResourceKind kind) {
  throwUseError(node, " uses " + quoted(res.name) + " as a " +
                          std::string(kind == ResourceKind::Texture ? "texture" : "buffer"));
}

[[noreturn, gnu::cold, gnu::noinline]] void throwUnwrittenRead(const NodeDecl& node, const ResourceDecl& res,
                                                               uint32_t version) {
  throwUseError(node, " reads " + quoted(res.name) + " version " + std::to_string(version) + ", which nobody wrote");
}

[[noreturn, gnu::cold, gnu::noinline]] void throwReadWithWritingAccess(const NodeDecl& node, Access access) {
  throwUseError(node, ": read() with a writing access " + std::string(toString(access)) + "; use write()");
}

[[noreturn, gnu::cold, gnu::noinline]] void throwWriteWithReadOnlyAccess(const NodeDecl& node, Access access) {
  throwUseError(node, ": write() with a read-only access " + std::string(toString(access)) + "; use read()");
}

[[noreturn, gnu::cold, gnu::noinline]] void throwUnknownAccess(const NodeDecl& node, Access access) {
  throwUseError(node, ": unknown access " + std::to_string(static_cast<int>(access)));
}

[[noreturn, gnu::cold, gnu::noinline]] void throwStaleWrite(const NodeDecl& node, const ResourceDecl& res,
                                                            uint32_t version) {
  throwUseError(node, " writes a stale version " + std::to_string(version) + " of " + quoted(res.name) +
                          " (latest is " + std::to_string(res.latestVersion) + ")");
}

}  // namespace

// Someone already wrote over `version`. Reading it back in the node that wrote over it (write,
// then read the old contents) orders nothing backwards; anything else might (conservatively: the
// compiler then computes a topological order instead of assuming the declaration order).
void FrameGraph::noteOldVersionRead(uint32_t node, uint32_t version, uint32_t latest) {
  const VersionDecl& newest = versions_[latest];
  if (newest.previous != version || newest.producer != node) readsOldVersions_ = true;
}

// The checks every use makes (the builder is the newest node's, the version exists, the handle's
// kind is the resource's) and what every use looks up: the version's resource and, for the
// node's type, what the access does.
struct FrameGraph::UseContext {
  NodeDecl& node;
  uint32_t nodeIndex;
  uint32_t resource;
  ResourceDecl& res;
  AccessInfo info;
};

// Inlined into its callers, like addRead and addWrite (below): every use pays for the call to
// read() or write() already, and a second call level (saving and restoring registers once more)
// cost a sixth of declaring a use.
[[gnu::always_inline]] inline FrameGraph::UseContext FrameGraph::beginUse(uint32_t node, uint32_t version,
                                                                        ResourceKind kind, Access access,
                                                                        StageMask stages) {
  NodeDecl& decl = nodes_[node];
  if (node + 1 != nodes_.size()) throwUseError(decl, ": its NodeBuilder was used after the next node was added");
  if (version >= versions_.size()) throwUnknownVersion(decl, kind, version);
  if (!detail::isKnownAccess(access)) throwUnknownAccess(decl, access);
  const uint32_t resource = versions_[version].resource;
  ResourceDecl& res = resources_[resource];
  if (res.kind != kind) throwWrongKind(decl, res, kind);
  return {decl, node, resource, res, detail::lookupUse(access, decl.type, stages)};
}

// Constructed in place: a Use built on the stack and copied in costs a store-forwarding stall.
[[gnu::always_inline]] inline void FrameGraph::recordUse(const UseContext& use, uint32_t readVersion,
                                                         uint32_t readProducer, uint32_t writeVersion, Access access,
                                                         StageMask stages) {
  append(allUses_, use.resource, readVersion, writeVersion, readProducer, stages, use.info.stages, use.info.access,
         access, use.info.layout);
  ++useStart_.back();
  // A node's uses are declared one after another, so a repeat finds itself as the last user.
  if (use.res.lastUser == use.nodeIndex) usesAResourceTwice_ = true;
  use.res.lastUser = use.nodeIndex;
}

// A read of `version` (which must have been written, or be an import's first version); returns
// the version's producer.
[[gnu::always_inline]] inline uint32_t FrameGraph::checkRead(const UseContext& use, uint32_t version) {
  const uint32_t producer = versions_[version].producer;
  const bool written = producer != kInvalidIndex || use.res.imported;
  if (!written) throwUnwrittenRead(use.node, use.res, version);
  if (version != use.res.latestVersion) noteOldVersionRead(use.nodeIndex, version, use.res.latestVersion);
  return producer;
}

[[gnu::always_inline]] inline uint32_t FrameGraph::addRead(uint32_t node, uint32_t version, ResourceKind kind,
                                                           Access access, StageMask stages) {
  const UseContext use = beginUse(node, version, kind, access, stages);
  if (use.info.writes) throwReadWithWritingAccess(use.node, access);
  const uint32_t producer = checkRead(use, version);
  recordUse(use, version, producer, kInvalidIndex, access, stages);
  return version;
}

// A write over `version` (which must be the latest); returns the version it creates. A
// read-modify-write access reads `version` too.
[[gnu::always_inline]] inline uint32_t FrameGraph::addWrite(uint32_t node, uint32_t version, ResourceKind kind,
                                                            Access access, StageMask stages) {
  const UseContext use = beginUse(node, version, kind, access, stages);
  if (!use.info.writes) throwWriteWithReadOnlyAccess(use.node, access);
  uint32_t readVersion = kInvalidIndex;
  uint32_t readProducer = kInvalidIndex;
  if (use.info.reads) {
    readProducer = checkRead(use, version);
    readVersion = version;
  }
  if (version != use.res.latestVersion) throwStaleWrite(use.node, use.res, version);
  const auto written = static_cast<uint32_t>(versions_.size());
  append(versions_, use.resource, node, version);
  use.res.latestVersion = written;
  recordUse(use, readVersion, readProducer, written, access, stages);
  return written;
}

// For the attachments, whose access is fixed by the call.
uint32_t FrameGraph::addUse(uint32_t node, uint32_t version, Access access) {
  return isWriteAccess(access) ? addWrite(node, version, ResourceKind::Texture, access, kStageNone)
                               : addRead(node, version, ResourceKind::Texture, access, kStageNone);
}

// ---- NodeBuilder ------------------------------------------------------------------------------

TextureHandle NodeBuilder::read(TextureHandle texture, Access access, StageMask stages) {
  return {graph_->addRead(node_, texture.version, ResourceKind::Texture, access, stages)};
}

BufferHandle NodeBuilder::read(BufferHandle buffer, Access access, StageMask stages) {
  return {graph_->addRead(node_, buffer.version, ResourceKind::Buffer, access, stages)};
}

TextureHandle NodeBuilder::write(TextureHandle texture, Access access, StageMask stages) {
  return {graph_->addWrite(node_, texture.version, ResourceKind::Texture, access, stages)};
}

BufferHandle NodeBuilder::write(BufferHandle buffer, Access access, StageMask stages) {
  return {graph_->addWrite(node_, buffer.version, ResourceKind::Buffer, access, stages)};
}

namespace {

void requireGraphicsNode(const NodeDecl& node, std::string_view what) {
  if (node.type != NodeType::Graphics) {
    throw GraphError("node " + quoted(node.name) + " is a " + std::string(toString(node.type)) +
                     " node; " + std::string(what) + " needs a graphics node");
  }
}

void requireNoDepthTarget(const FrameGraph& graph, uint32_t node) {
  const NodeDecl& decl = graph.nodes()[node];
  requireGraphicsNode(decl, "a depth target");
  if (graph.attachments(node).depth.target.valid()) {
    throw GraphError("node " + quoted(decl.name) + " has two depth targets");
  }
}

}  // namespace

TextureHandle NodeBuilder::addColorTarget(TextureHandle target, LoadOp load, ClearValue clear) {
  requireGraphicsNode(graph_->nodes_[node_], "a colour target");
  const Access access = load == LoadOp::Load ? Access::ColorAttachmentReadWrite : Access::ColorAttachmentWrite;
  const TextureHandle written{graph_->addUse(node_, target.version, access)};
  graph_->newestNodeAttachments(node_).color.push_back({written, {}, load, StoreOp::Store, clear});
  return written;
}

TextureHandle NodeBuilder::addColorTargetWithResolve(TextureHandle target, TextureHandle resolveTarget,
                                                     TextureHandle* newTargetVersion, LoadOp load,
                                                     ClearValue clear) {
  const TextureHandle written = addColorTarget(target, load, clear);
  if (newTargetVersion != nullptr) *newTargetVersion = written;
  const TextureHandle resolved{graph_->addUse(node_, resolveTarget.version, Access::ResolveDst)};
  graph_->newestNodeAttachments(node_).color.back().resolveTarget = resolved;
  return resolved;
}

TextureHandle NodeBuilder::setDepthStencil(TextureHandle target, LoadOp load, ClearValue clear) {
  requireNoDepthTarget(*graph_, node_);
  const Access access = load == LoadOp::Load ? Access::DepthAttachmentReadWrite : Access::DepthAttachmentWrite;
  const TextureHandle written{graph_->addUse(node_, target.version, access)};
  graph_->newestNodeAttachments(node_).depth = {written, load, StoreOp::Store, clear, false};
  return written;
}

void NodeBuilder::setDepthStencilReadOnly(TextureHandle target) {
  requireNoDepthTarget(*graph_, node_);
  graph_->addUse(node_, target.version, Access::DepthAttachmentRead);
  graph_->newestNodeAttachments(node_).depth = {target, LoadOp::Load, StoreOp::Store, {}, true};
}

NodeBuilder& NodeBuilder::sideEffect() {
  graph_->nodes_[node_].sideEffect = true;
  return *this;
}

NodeBuilder& NodeBuilder::setJob(Job job) {
  auto& jobs = graph_->jobs_;
  if (jobs.size() <= node_) jobs.resize(node_ + 1);
  jobs[node_] = std::move(job);
  return *this;
}

}  // namespace fgb::graph
