#include <fgb/graph/frame_graph.hpp>

#include "access_table.hpp"
#include "vector_pool.hpp"

#include <string>

namespace fgb::graph {
namespace {

std::string quoted(std::string_view name) { return "'" + std::string(name) + "'"; }

}  // namespace

// ---- FrameGraph -------------------------------------------------------------------------------

FrameGraph::FrameGraph() {
  detail::VectorPool<NodeDecl>::take(nodes_);
  detail::VectorPool<ResourceDecl>::take(resources_);
  detail::VectorPool<VersionDecl>::take(versions_);
  detail::VectorPool<Use>::take(allUses_);
  detail::VectorPool<uint32_t>::take(useStart_);
  useStart_.push_back(0);  // node 0's first use
}

FrameGraph::~FrameGraph() {
  detail::VectorPool<NodeDecl>::give(nodes_);
  detail::VectorPool<ResourceDecl>::give(resources_);
  detail::VectorPool<VersionDecl>::give(versions_);
  detail::VectorPool<Use>::give(allUses_);
  detail::VectorPool<uint32_t>::give(useStart_);
}

void FrameGraph::reserve(size_t nodes, size_t resources) {
  nodes_.reserve(nodes);
  resources_.reserve(resources);
  versions_.reserve(resources + nodes);
  allUses_.reserve(nodes * 3);
  useStart_.reserve(nodes + 1);
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
                                                                    bool imported) {
  const auto resource = static_cast<uint32_t>(resources_.size());
  const auto version = static_cast<uint32_t>(versions_.size());
  versions_.emplace_back().resource = resource;  // a first version: no producer, no previous
  // Copied from a blank one rather than value-initialised in place: the compiler clears a struct
  // this large with `rep stos`, which costs several times more per declaration than a copy.
  static const ResourceDecl kBlank{};
  ResourceDecl& decl = resources_.emplace_back(kBlank);
  decl.name = name;  // the caller fills in the description
  decl.kind = kind;
  decl.imported = imported;
  decl.firstVersion = version;
  decl.latestVersion = version;
  return decl;
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
  ResourceDecl& decl = addResource(name, ResourceKind::Texture, true);
  decl.texture = desc;
  decl.external = external;
  decl.initialState = initial;
  decl.finalState = final;
  return {decl.firstVersion};
}

BufferHandle FrameGraph::importBuffer(std::string_view name, const BufferDesc& desc, ExternalResource external,
                                      ImportState initial, ImportState final) {
  ResourceDecl& decl = addResource(name, ResourceKind::Buffer, true);
  decl.buffer = desc;
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
  ResourceDecl& decl = addResource(name, ResourceKind::Texture, false);
  decl.texture = desc;
  return {decl.firstVersion};
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
  ResourceDecl& decl = addResource(name, ResourceKind::Buffer, false);
  decl.buffer = desc;
  return {decl.firstVersion};
}

NodeBuilder FrameGraph::addNode(std::string_view name, NodeType type) {
  return addNode(name, type, defaultQueue(type));
}

NodeBuilder FrameGraph::addNode(std::string_view name, NodeType type, QueueClass queue) {
  const auto node = static_cast<uint32_t>(nodes_.size());
  // Copied from a blank one, like a resource (see addResource).
  static const NodeDecl kBlank{};
  NodeDecl& decl = nodes_.emplace_back(kBlank);
  decl.name = name;
  decl.type = type;
  decl.queue = queue;
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

// Inlined into its callers (read, write, the attachments): every use pays for the call to one of
// those already, and a second call level (saving and restoring registers once more) cost a sixth of
// declaring a use.
[[gnu::always_inline]] inline uint32_t FrameGraph::addUse(uint32_t node, uint32_t version, ResourceKind kind,
                                                          Access access, StageMask stages) {
  NodeDecl& decl = nodes_[node];
  if (node + 1 != nodes_.size()) throwUseError(decl, ": its NodeBuilder was used after the next node was added");
  if (version >= versions_.size()) throwUnknownVersion(decl, kind, version);
  const uint32_t resource = versions_[version].resource;
  ResourceDecl& res = resources_[resource];
  if (res.kind != kind) throwWrongKind(decl, res, kind);
  const AccessInfo info = detail::lookupAccessInfo(access, decl.type, stages);
  uint32_t readVersion = kInvalidIndex;
  uint32_t writeVersion = kInvalidIndex;
  if (info.reads) {
    const bool written = versions_[version].producer != kInvalidIndex || res.imported;
    if (!written) throwUnwrittenRead(decl, res, version);
    readVersion = version;
    if (version != res.latestVersion) noteOldVersionRead(node, version, res.latestVersion);
  }
  if (info.writes) {
    if (version != res.latestVersion) throwStaleWrite(decl, res, version);
    writeVersion = static_cast<uint32_t>(versions_.size());
    VersionDecl& written = versions_.emplace_back();
    written.resource = resource;
    written.producer = node;
    written.previous = version;
    res.latestVersion = writeVersion;
  }
  // Filled in place: a Use built on the stack and copied in costs a store-forwarding stall.
  Use& use = allUses_.emplace_back();
  use.resource = resource;
  use.readVersion = readVersion;
  use.writeVersion = writeVersion;
  use.access = access;
  use.shaderStages = stages;
  use.stages = info.stages;
  use.accessMask = info.access;
  use.layout = info.layout;
  ++useStart_.back();
  return info.writes ? writeVersion : version;
}

// ---- NodeBuilder ------------------------------------------------------------------------------

TextureHandle NodeBuilder::read(TextureHandle texture, Access access, StageMask stages) {
  if (isWriteAccess(access)) {
    throw GraphError("node " + quoted(graph_->nodes_[node_].name) + ": read() with a writing access " +
                     std::string(toString(access)) + "; use write()");
  }
  return {graph_->addUse(node_, texture.version, ResourceKind::Texture, access, stages)};
}

BufferHandle NodeBuilder::read(BufferHandle buffer, Access access, StageMask stages) {
  if (isWriteAccess(access)) {
    throw GraphError("node " + quoted(graph_->nodes_[node_].name) + ": read() with a writing access " +
                     std::string(toString(access)) + "; use write()");
  }
  return {graph_->addUse(node_, buffer.version, ResourceKind::Buffer, access, stages)};
}

TextureHandle NodeBuilder::write(TextureHandle texture, Access access, StageMask stages) {
  if (!isWriteAccess(access)) {
    throw GraphError("node " + quoted(graph_->nodes_[node_].name) + ": write() with a read-only access " +
                     std::string(toString(access)) + "; use read()");
  }
  return {graph_->addUse(node_, texture.version, ResourceKind::Texture, access, stages)};
}

BufferHandle NodeBuilder::write(BufferHandle buffer, Access access, StageMask stages) {
  if (!isWriteAccess(access)) {
    throw GraphError("node " + quoted(graph_->nodes_[node_].name) + ": write() with a read-only access " +
                     std::string(toString(access)) + "; use read()");
  }
  return {graph_->addUse(node_, buffer.version, ResourceKind::Buffer, access, stages)};
}

namespace {

void requireGraphicsNode(const NodeDecl& node, std::string_view what) {
  if (node.type != NodeType::Graphics) {
    throw GraphError("node " + quoted(node.name) + " is a " + std::string(toString(node.type)) +
                     " node; " + std::string(what) + " needs a graphics node");
  }
}

}  // namespace

TextureHandle NodeBuilder::addColorTarget(TextureHandle target, LoadOp load, ClearValue clear) {
  requireGraphicsNode(graph_->nodes_[node_], "a colour target");
  const Access access = load == LoadOp::Load ? Access::ColorAttachmentReadWrite : Access::ColorAttachmentWrite;
  const TextureHandle written{graph_->addUse(node_, target.version, ResourceKind::Texture, access, kStageNone)};
  graph_->nodes_[node_].colorAttachments.push_back({written, {}, load, StoreOp::Store, clear});
  return written;
}

TextureHandle NodeBuilder::addColorTargetWithResolve(TextureHandle target, TextureHandle resolveTarget,
                                                     TextureHandle* newTargetVersion, LoadOp load,
                                                     ClearValue clear) {
  const TextureHandle written = addColorTarget(target, load, clear);
  if (newTargetVersion != nullptr) *newTargetVersion = written;
  const TextureHandle resolved{
      graph_->addUse(node_, resolveTarget.version, ResourceKind::Texture, Access::ResolveDst, kStageNone)};
  graph_->nodes_[node_].colorAttachments.back().resolveTarget = resolved;
  return resolved;
}

TextureHandle NodeBuilder::setDepthStencil(TextureHandle target, LoadOp load, ClearValue clear) {
  NodeDecl& node = graph_->nodes_[node_];
  requireGraphicsNode(node, "a depth target");
  if (node.depthAttachment.target.valid()) throw GraphError("node " + quoted(node.name) + " has two depth targets");
  const Access access = load == LoadOp::Load ? Access::DepthAttachmentReadWrite : Access::DepthAttachmentWrite;
  const TextureHandle written{graph_->addUse(node_, target.version, ResourceKind::Texture, access, kStageNone)};
  graph_->nodes_[node_].depthAttachment = {written, load, StoreOp::Store, clear, false};
  return written;
}

void NodeBuilder::setDepthStencilReadOnly(TextureHandle target) {
  NodeDecl& node = graph_->nodes_[node_];
  requireGraphicsNode(node, "a depth target");
  if (node.depthAttachment.target.valid()) throw GraphError("node " + quoted(node.name) + " has two depth targets");
  graph_->addUse(node_, target.version, ResourceKind::Texture, Access::DepthAttachmentRead, kStageNone);
  graph_->nodes_[node_].depthAttachment = {target, LoadOp::Load, StoreOp::Store, {}, true};
}

NodeBuilder& NodeBuilder::sideEffect() {
  graph_->nodes_[node_].sideEffect = true;
  return *this;
}

NodeBuilder& NodeBuilder::setJob(Job job) {
  graph_->nodes_[node_].job = std::move(job);
  return *this;
}

}  // namespace fgb::graph
