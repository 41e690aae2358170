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

// Element `index` of an array indexed by node that only grows as far as some node needs it.
template <typename T>
T& grownTo(std::vector<T>& array, uint32_t index) {
  if (array.size() <= index) array.resize(index + 1);
  return array[index];
}

}  // namespace

FrameGraph::FrameGraph() : useStart_{0} {}  // node 0's uses start at 0
FrameGraph::~FrameGraph() = default;
FrameGraph::FrameGraph(const FrameGraph& other) = default;
FrameGraph& FrameGraph::operator=(const FrameGraph& other) = default;
FrameGraph::FrameGraph(FrameGraph&& other) noexcept = default;
FrameGraph& FrameGraph::operator=(FrameGraph&& other) noexcept = default;

void FrameGraph::reserve(size_t nodes, size_t resources) {
  nodes_.reserve(nodes);
  resources_.reserve(resources);
  versions_.reserve(resources + nodes);
  uses_.reserve(nodes * 3);
  useStart_.reserve(nodes + 1);
}

std::vector<ResourceAccess> FrameGraph::accesses(uint32_t node) const {
  std::vector<ResourceAccess> accesses;
  for (const Use& use : detail::Declared::uses(*this, node)) accesses.push_back({use.resource, use.access});
  return accesses;
}

uint32_t FrameGraph::resourceOf(TextureHandle h) const {
  return versionAt(h.version, "texture").resource;
}
uint32_t FrameGraph::resourceOf(BufferHandle h) const {
  return versionAt(h.version, "buffer").resource;
}

const NodeAttachments& FrameGraph::attachments(uint32_t node) const {
  static const NodeAttachments kNone{};
  return node < attachments_.size() ? attachments_[node] : kNone;
}

std::vector<Job> FrameGraph::takeJobs() {
  std::vector<Job> jobs = std::move(jobs_);
  jobs.resize(nodes_.size());
  jobs_.clear();
  return jobs;
}

const VersionDecl& FrameGraph::versionAt(uint32_t version, std::string_view what) const {
  if (version >= versions_.size())
    throw GraphError("unknown " + std::string(what) + " version " + versionText(version));
  return versions_[version];
}

uint32_t FrameGraph::addResource(ResourceDecl decl) {
  const auto version = static_cast<uint32_t>(versions_.size());
  versions_.push_back({static_cast<uint32_t>(resources_.size()), kInvalidIndex, kInvalidIndex});
  decl.firstVersion = decl.latestVersion = version;
  resources_.push_back(std::move(decl));
  return version;
}

// A dependent field (extentFrom, sizeFrom) must name a version of a resource of the same kind,
// declared before: the compiler resolves resources in declaration order.
void FrameGraph::checkDependentField(std::string_view name, ResourceKind kind, std::string_view field,
                                     uint32_t version) const {
  const std::string what = kindName(kind) + " " + quoted(name) + ": dependent field " + std::string(field) + " names ";
  if (version >= versions_.size()) throw GraphError(what + "unknown resource version " + std::to_string(version));
  const ResourceDecl& source = resources_[versions_[version].resource];
  if (source.kind != kind) {
    throw GraphError(what + kindName(source.kind) + " " + quoted(source.name) + ", not a " + kindName(kind));
  }
}

TextureHandle FrameGraph::importTexture(std::string_view name, const TextureDesc& desc, ExternalResource external,
                                        ImportState initial, ImportState final) {
  if (desc.extentFrom.valid()) checkDependentField(name, ResourceKind::Texture, "extentFrom", desc.extentFrom.version);
  return {addResource({std::string(name), ResourceKind::Texture, true, desc, {}, external, initial, final})};
}

BufferHandle FrameGraph::importBuffer(std::string_view name, const BufferDesc& desc, ExternalResource external,
                                      ImportState initial, ImportState final) {
  if (desc.sizeFrom.valid()) checkDependentField(name, ResourceKind::Buffer, "sizeFrom", desc.sizeFrom.version);
  return {addResource({std::string(name), ResourceKind::Buffer, true, {}, desc, external, initial, final})};
}

TextureHandle FrameGraph::createTexture(std::string_view name, const TextureDesc& desc) {
  if (desc.extentFrom.valid()) {
    checkDependentField(name, ResourceKind::Texture, "extentFrom", desc.extentFrom.version);
  } else if (desc.format == Format::Undefined) {
    throw GraphError("texture " + quoted(name) + ": format is UNDEFINED");
  }
  return {addResource({std::string(name), ResourceKind::Texture, false, desc})};
}

BufferHandle FrameGraph::createBuffer(std::string_view name, const BufferDesc& desc) {
  if (desc.sizeFrom.valid()) {
    checkDependentField(name, ResourceKind::Buffer, "sizeFrom", desc.sizeFrom.version);
  } else if (desc.size == 0) {
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
  if (access > Access::HostRead) failUse(decl, ": unknown access " + std::to_string(static_cast<int>(access)));
  const ResourceDecl& res = resources_[versions_[version].resource];
  if (res.kind != kind) failUse(decl, " uses " + quoted(res.name) + " as a " + kindName(kind));
  return res;
}

// A read must find its version written (or be of an import's first version).
void FrameGraph::checkWritten(uint32_t node, const ResourceDecl& res, uint32_t version) const {
  if (versions_[version].producer == kInvalidIndex && !res.imported) {
    failUse(nodes_[node],
            " reads " + quoted(res.name) + " version " + std::to_string(version) + ", which nobody wrote");
  }
}

void FrameGraph::recordUse(uint32_t node, uint32_t resource, uint32_t readVersion, uint32_t writeVersion, Access access,
                           StageMask stages) {
  const AccessInfo info = accessInfo(access, nodes_[node].type, stages);
  uses_.push_back({resource, readVersion, writeVersion, stages, info.stages, info.access, access, info.layout});
  ++useStart_.back();
}

uint32_t FrameGraph::addRead(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages) {
  const ResourceDecl& res = checkUse(node, version, kind, access);
  if (isWriteAccess(access)) {
    failUse(nodes_[node], ": read() with a writing access " + std::string(toString(access)) + "; use write()");
  }
  checkWritten(node, res, version);
  recordUse(node, versions_[version].resource, version, kInvalidIndex, access, stages);
  return version;
}

// A write over `version`, which must be the latest; returns the version it creates. A
// read-modify-write access reads `version` too.
uint32_t FrameGraph::addWrite(uint32_t node, uint32_t version, ResourceKind kind, Access access, StageMask stages) {
  const ResourceDecl& res = checkUse(node, version, kind, access);
  const AccessInfo info = accessInfo(access, nodes_[node].type);
  if (!info.writes) {
    failUse(nodes_[node], ": write() with a read-only access " + std::string(toString(access)) + "; use read()");
  }
  if (info.reads) checkWritten(node, res, version);
  if (version != res.latestVersion) {
    failUse(nodes_[node], " writes a stale version " + std::to_string(version) + " of " + quoted(res.name) +
                              " (latest is " + std::to_string(res.latestVersion) + ")");
  }
  const uint32_t resource = versions_[version].resource;
  const auto written = static_cast<uint32_t>(versions_.size());
  versions_.push_back({resource, node, version});
  resources_[resource].latestVersion = written;
  recordUse(node, resource, info.reads ? version : kInvalidIndex, written, access, stages);
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
    throw GraphError("node " + quoted(node.name) + " is a " + std::string(toString(node.type)) + " node; " +
                     std::string(what) + " needs a graphics node");
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
  grownTo(graph_->attachments_, node_).color.push_back({written, {}, load, StoreOp::Store, clear});
  return written;
}

TextureHandle NodeBuilder::addColorTargetWithResolve(TextureHandle target, TextureHandle resolveTarget,
                                                     TextureHandle* newTargetVersion, LoadOp load, ClearValue clear) {
  const TextureHandle written = addColorTarget(target, load, clear);
  if (newTargetVersion != nullptr) *newTargetVersion = written;
  const TextureHandle resolved{graph_->addUse(node_, resolveTarget.version, Access::ResolveDst)};
  grownTo(graph_->attachments_, node_).color.back().resolveTarget = resolved;
  return resolved;
}

TextureHandle NodeBuilder::setDepthStencil(TextureHandle target, LoadOp load, ClearValue clear) {
  requireNoDepthTarget(*graph_, node_);
  const Access access = load == LoadOp::Load ? Access::DepthAttachmentReadWrite : Access::DepthAttachmentWrite;
  const TextureHandle written{graph_->addUse(node_, target.version, access)};
  grownTo(graph_->attachments_, node_).depth = {written, load, StoreOp::Store, clear, false};
  return written;
}

void NodeBuilder::setDepthStencilReadOnly(TextureHandle target) {
  requireNoDepthTarget(*graph_, node_);
  graph_->addUse(node_, target.version, Access::DepthAttachmentRead);
  grownTo(graph_->attachments_, node_).depth = {target, LoadOp::Load, StoreOp::Store, {}, true};
}

NodeBuilder& NodeBuilder::sideEffect() {
  graph_->nodes_[node_].sideEffect = true;
  return *this;
}

NodeBuilder& NodeBuilder::setJob(Job job) {
  grownTo(graph_->jobs_, node_) = std::move(job);
  return *this;
}

}  // namespace fgb::graph
