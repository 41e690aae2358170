#include <string>
#include <utility>

#include "declaration.hpp"

namespace fgb::graph {
namespace {

using detail::Use;
using detail::VersionDecl;

std::string quoted(std::string_view name) {
  return std::string("'").append(name).append("'");
}

std::string kindName(ResourceKind kind) {
  return kind == ResourceKind::Texture ? "texture" : "buffer";
}

std::string versionText(uint32_t version) {
  return version == kInvalidIndex ? std::string("(invalid handle)") : std::to_string(version);
}

// Declaration errors name the node first.
[[noreturn]] void failUse(const NodeDecl& node, const std::string& what) {
  throw GraphError("node " + quoted(node.name) + what);
}

void requireGraphicsNode(const NodeDecl& node, const char* what) {
  if (node.type != NodeType::Graphics) {
    failUse(node, " is a " + std::string(toString(node.type)) + " node; " + what + " needs a graphics node");
  }
}

void requireNoDepthTarget(const FrameGraph& graph, uint32_t node) {
  const NodeDecl& decl = graph.nodes()[node];
  requireGraphicsNode(decl, "a depth target");
  if (graph.attachments(node).depth.target.valid()) failUse(decl, " has two depth targets");
}

}  // namespace

FrameGraph::FrameGraph() : useStart_{0} {}  // node 0's uses start at 0
FrameGraph::~FrameGraph() = default;
FrameGraph::FrameGraph(const FrameGraph& other) = default;
FrameGraph& FrameGraph::operator=(const FrameGraph& other) = default;
FrameGraph::FrameGraph(FrameGraph&& other) noexcept = default;
FrameGraph& FrameGraph::operator=(FrameGraph&& other) noexcept = default;

std::vector<ResourceAccess> FrameGraph::accesses(uint32_t node) const {
  std::vector<ResourceAccess> accesses;
  for (const Use& use : detail::Declared::uses(*this, node))
    accesses.push_back({use.resource, use.access, use.readVersion, use.writeVersion});
  return accesses;
}

uint32_t FrameGraph::resourceOf(uint32_t version, const char* kind) const {
  if (version >= versions_.size())
    throw GraphError("unknown " + std::string(kind) + " version " + versionText(version));
  return versions_[version].resource;
}

uint32_t FrameGraph::addResource(ResourceDecl decl) {
  checkDependentField(decl);
  const auto version = static_cast<uint32_t>(versions_.size());
  versions_.push_back({static_cast<uint32_t>(resources_.size()), kInvalidIndex, kInvalidIndex});
  decl.firstVersion = decl.latestVersion = version;
  resources_.push_back(std::move(decl));
  return version;
}

// A dependent field (extentFrom, sizeFrom), when set, must name a version of a resource of the same
// kind, declared before: the compiler resolves resources in declaration order.
void FrameGraph::checkDependentField(const ResourceDecl& decl) const {
  const bool texture = decl.kind == ResourceKind::Texture;
  const uint32_t version = texture ? decl.texture.extentFrom.version : decl.buffer.sizeFrom.version;
  if (version == kInvalidIndex) return;
  const std::string field = texture ? "extentFrom" : "sizeFrom";
  const std::string what = kindName(decl.kind) + " " + quoted(decl.name) + ": dependent field " + field + " names ";
  if (version >= versions_.size()) throw GraphError(what + "unknown resource version " + std::to_string(version));
  const ResourceDecl& source = resources_[versions_[version].resource];
  if (source.kind != decl.kind) {
    throw GraphError(what + kindName(source.kind) + " " + quoted(source.name) + ", not a " + kindName(decl.kind));
  }
}

TextureHandle FrameGraph::importTexture(std::string_view name, const TextureDesc& desc, ExternalResource external,
                                        ImportState initial, ImportState final) {
  return {addResource({std::string(name), ResourceKind::Texture, true, desc, {}, external, initial, final})};
}

BufferHandle FrameGraph::importBuffer(std::string_view name, const BufferDesc& desc, ExternalResource external,
                                      ImportState initial, ImportState final) {
  return {addResource({std::string(name), ResourceKind::Buffer, true, {}, desc, external, initial, final})};
}

TextureHandle FrameGraph::createTexture(std::string_view name, const TextureDesc& desc) {
  if (!desc.extentFrom.valid() && desc.format == Format::Undefined) {
    throw GraphError("texture " + quoted(name) + ": format is UNDEFINED");
  }
  return {addResource({std::string(name), ResourceKind::Texture, false, desc})};
}

BufferHandle FrameGraph::createBuffer(std::string_view name, const BufferDesc& desc) {
  if (!desc.sizeFrom.valid() && desc.size == 0) {
    throw GraphError("buffer " + quoted(name) + ": size is 0");
  }
  return {addResource({std::string(name), ResourceKind::Buffer, false, {}, desc})};
}

NodeBuilder FrameGraph::addNode(std::string_view name, NodeType type) {
  return addNode(name, type, defaultQueue(type));
}

NodeBuilder FrameGraph::addNode(std::string_view name, NodeType type, QueueClass queue) {
  // Checked once here, so that the compiler can index tables by a node's queue class.
  if (type > NodeType::Transfer || static_cast<uint32_t>(queue) >= kQueueClassCount) {
    throw GraphError("node " + quoted(name) + ": unknown node type " + std::to_string(static_cast<int>(type)) +
                     " or queue class " + std::to_string(static_cast<int>(queue)));
  }
  const auto node = static_cast<uint32_t>(nodes_.size());
  nodes_.push_back({std::string(name), type, queue, false});
  attachments_.emplace_back();
  jobs_.emplace_back();
  recordingKeys_.emplace_back();
  if (useStart_.empty()) useStart_.push_back(0);  // a moved-from graph being reused
  useStart_.push_back(useStart_.back());          // the new node's end, moved on by each of its uses
  return NodeBuilder(*this, node);
}

// The checks every use makes: the builder is the newest node's, the version exists, the access is
// known, and the handle's kind is the resource's. Returns the version's resource.
const ResourceDecl& FrameGraph::checkUse(uint32_t node, uint32_t version, ResourceKind kind, Access access) const {
  const NodeDecl& decl = nodes_[node];
  if (node + 1 != nodes_.size()) failUse(decl, ": its NodeBuilder was used after the next node was added");
  if (version >= versions_.size())
    failUse(decl, " uses an unknown " + kindName(kind) + " version " + versionText(version));
  if (access > kLastAccess) failUse(decl, ": unknown access " + std::to_string(static_cast<int>(access)));
  const ResourceDecl& res = resources_[versions_[version].resource];
  if (res.kind != kind) failUse(decl, " uses " + quoted(res.name) + " as a " + kindName(kind));
  return res;
}

// A use of `version` by the newest node, declared through write() (`write`) or read(): returns the
// version it creates, or the version it reads. A read-modify-write access reads `version` too.
uint32_t FrameGraph::addUse(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages,
                            bool write) {
  const ResourceDecl& res = checkUse(node, version, kind, access);
  const NodeDecl& decl = nodes_[node];
  const AccessInfo info = accessInfo(access, decl.type, stages);
  const std::string accessName(toString(access));
  if (write && !info.writes) failUse(decl, ": write() with a read-only access " + accessName + "; use read()");
  if (!write && info.writes) failUse(decl, ": read() with a writing access " + accessName + "; use write()");
  if (info.reads && versions_[version].producer == kInvalidIndex && !res.imported) {
    failUse(decl, " reads " + quoted(res.name) + " version " + std::to_string(version) + ", which nobody wrote");
  }
  const uint32_t resource = versions_[version].resource;
  uint32_t written = kInvalidIndex;
  if (write) {
    if (version != res.latestVersion) {
      failUse(decl, " writes a stale version " + std::to_string(version) + " of " + quoted(res.name) + " (latest is " +
                        std::to_string(res.latestVersion) + ")");
    }
    written = static_cast<uint32_t>(versions_.size());
    versions_.push_back({resource, node, version});
    resources_[resource].latestVersion = written;
  }
  const uint32_t read = info.reads ? version : kInvalidIndex;
  uses_.push_back({resource, read, written, stages, info.stages, info.access, access, info.layout});
  ++useStart_.back();
  return write ? written : version;
}

// An attachment's use: a texture, written or not as the access says.
uint32_t FrameGraph::addAttachmentUse(uint32_t node, uint32_t version, Access access) {
  return addUse(node, version, ResourceKind::Texture, access, kStageNone, isWriteAccess(access));
}

// ---- NodeBuilder ------------------------------------------------------------------------------

TextureHandle NodeBuilder::read(TextureHandle texture, Access access, StageMask stages) {
  return {graph_->addUse(node_, texture.version, ResourceKind::Texture, access, stages, false)};
}

BufferHandle NodeBuilder::read(BufferHandle buffer, Access access, StageMask stages) {
  return {graph_->addUse(node_, buffer.version, ResourceKind::Buffer, access, stages, false)};
}

TextureHandle NodeBuilder::write(TextureHandle texture, Access access, StageMask stages) {
  return {graph_->addUse(node_, texture.version, ResourceKind::Texture, access, stages, true)};
}

BufferHandle NodeBuilder::write(BufferHandle buffer, Access access, StageMask stages) {
  return {graph_->addUse(node_, buffer.version, ResourceKind::Buffer, access, stages, true)};
}

TextureHandle NodeBuilder::addColorTarget(TextureHandle target, LoadOp load, ClearValue clear) {
  requireGraphicsNode(graph_->nodes_[node_], "a colour target");
  const Access access = load == LoadOp::Load ? Access::ColorAttachmentReadWrite : Access::ColorAttachmentWrite;
  const TextureHandle written{graph_->addAttachmentUse(node_, target.version, access)};
  graph_->attachments_[node_].color.push_back({written, {}, load, StoreOp::Store, clear});
  return written;
}

TextureHandle NodeBuilder::addColorTargetWithResolve(TextureHandle target, TextureHandle resolveTarget,
                                                     TextureHandle* newTargetVersion, LoadOp load, ClearValue clear) {
  const TextureHandle written = addColorTarget(target, load, clear);
  if (newTargetVersion != nullptr) *newTargetVersion = written;
  const TextureHandle resolved{graph_->addAttachmentUse(node_, resolveTarget.version, Access::ResolveDst)};
  graph_->attachments_[node_].color.back().resolveTarget = resolved;
  return resolved;
}

TextureHandle NodeBuilder::setDepthStencil(TextureHandle target, LoadOp load, ClearValue clear) {
  requireNoDepthTarget(*graph_, node_);
  const Access access = load == LoadOp::Load ? Access::DepthAttachmentReadWrite : Access::DepthAttachmentWrite;
  const TextureHandle written{graph_->addAttachmentUse(node_, target.version, access)};
  graph_->attachments_[node_].depth = {written, load, StoreOp::Store, clear, false};
  return written;
}

void NodeBuilder::setDepthStencilReadOnly(TextureHandle target) {
  requireNoDepthTarget(*graph_, node_);
  graph_->addAttachmentUse(node_, target.version, Access::DepthAttachmentRead);
  graph_->attachments_[node_].depth = {target, LoadOp::Load, StoreOp::Store, {}, true};
}

NodeBuilder& NodeBuilder::sideEffect() {
  graph_->nodes_[node_].sideEffect = true;
  return *this;
}

NodeBuilder& NodeBuilder::setJob(Job job) {
  graph_->jobs_[node_] = std::move(job);
  return *this;
}

NodeBuilder& NodeBuilder::recordingDependsOn(RecordingKey key) {
  graph_->recordingKeys_[node_] = std::move(key);
  return *this;
}

}  // namespace fgb::graph
