#include "random_graph.hpp"

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace fgb::graph::test {
namespace {

// Per-resource bookkeeping: the handle of each chain position, for reading old versions.
struct ResourceState {
  ResourceKind kind = ResourceKind::Texture;
  bool imported = false;
  bool depth = false;
  std::vector<uint32_t> versions;  // handle of chain position k
};

class Generator {
 public:
  Generator(uint32_t seed, const RandomGraphParams& params) : rng_(seed), params_(params) {
    result_.graph = std::make_unique<FrameGraph>();
  }

  RandomGraph run() {
    const uint32_t resourceCount = params_.nodes / 2 + 3;
    for (uint32_t r = 0; r < resourceCount; ++r) declareResource(r);
    for (uint32_t n = 0; n < params_.nodes; ++n) declareNode(n);
    return std::move(result_);
  }

 private:
  uint32_t below(uint32_t bound) { return static_cast<uint32_t>(rng_() % bound); }
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  FrameGraph& graph() { return *result_.graph; }

  void declareResource(uint32_t index) {
    ResourceState state;
    state.kind = below(3) == 0 ? ResourceKind::Buffer : ResourceKind::Texture;
    state.imported = below(4) == 0 || index == 0;  // at least one output exists
    const std::string name = (state.imported ? "imp" : "tr") + std::to_string(index);
    uint32_t handle = state.kind == ResourceKind::Texture ? declareTexture(name, state) : declareBuffer(name, state);
    state.versions.push_back(handle);
    result_.model.resourceName.push_back(name);
    result_.model.kind.push_back(state.kind);
    result_.model.imported.push_back(state.imported);
    resources_.push_back(std::move(state));
  }

  // A dependent field on a transient names an earlier resource of the same kind (maybe dependent itself).
  int dependentSource(ResourceKind kind) {
    std::vector<uint32_t> candidates;
    for (uint32_t r = 0; r < resources_.size(); ++r) {
      if (resources_[r].kind == kind) candidates.push_back(r);
    }
    if (candidates.empty() || !chance(0.3)) return -1;
    return static_cast<int>(candidates[below(static_cast<uint32_t>(candidates.size()))]);
  }

  uint32_t declareTexture(const std::string& name, ResourceState& state) {
    static constexpr Format kColor[] = {Format::R8G8B8A8Unorm, Format::R16G16B16A16Sfloat, Format::R32Sfloat,
                                        Format::B10G11R11UfloatPack32};
    static constexpr uint32_t kSizes[] = {64, 128, 256, 512};
    state.depth = below(5) == 0;
    TextureDesc desc;
    desc.format = state.depth ? Format::D32Sfloat : kColor[below(4)];
    desc.extent = {kSizes[below(4)], kSizes[below(4)], 1};
    if (state.imported) {
      const ImportState initial{.layout = below(2) == 0 ? Layout::Undefined : Layout::ShaderReadOnly};
      const ImportState final{.layout = state.depth ? Layout::DepthStencilAttachment : Layout::ShaderReadOnly};
      return graph().importTexture(name, desc, {index()}, initial, final).version;
    }
    if (const int source = dependentSource(ResourceKind::Texture); source >= 0) {
      desc.extentFrom = TextureHandle{resources_[static_cast<uint32_t>(source)].versions[0]};
      desc.extentShift = below(3);
    }
    return graph().createTexture(name, desc).version;
  }

  uint32_t declareBuffer(const std::string& name, const ResourceState& state) {
    BufferDesc desc;
    desc.size = 256u * (1u + below(256));
    if (state.imported) return graph().importBuffer(name, desc, {index()}, {}, {}).version;
    if (const int source = dependentSource(ResourceKind::Buffer); source >= 0) {
      desc.sizeFrom = BufferHandle{resources_[static_cast<uint32_t>(source)].versions[0]};
    }
    return graph().createBuffer(name, desc).version;
  }

  uint64_t index() const { return resources_.size(); }

  static NodeType pickType(uint32_t roll) {
    if (roll < 50) return NodeType::Graphics;
    return roll < 85 ? NodeType::Compute : NodeType::Transfer;
  }

  QueueClass pickClass(NodeType type) {
    if (type == NodeType::Graphics || !chance(0.15)) return defaultQueue(type);
    if (type == NodeType::Compute) return QueueClass::Graphics;
    return below(2) == 0 ? QueueClass::Graphics : QueueClass::Compute;
  }

  void declareNode(uint32_t n) {
    const NodeType type = pickType(below(100));
    const QueueClass queueClass = pickClass(type);
    const std::string name = std::string("n").append(std::to_string(n));
    NodeBuilder builder = graph().addNode(name, type, queueClass);
    result_.model.nodeName.push_back(name);
    result_.model.nodeType.push_back(type);
    result_.model.nodeClass.push_back(queueClass);
    std::vector<uint32_t> used;
    const uint32_t reads = below(3);
    const uint32_t writes = chance(0.9) ? 1 + below(2) : 0;
    for (uint32_t i = 0; i < reads; ++i) addRead(builder, n, type, used);
    for (uint32_t i = 0; i < writes; ++i) addWrite(builder, n, type, used);
    const bool sideEffect = chance(params_.sideEffectChance);
    if (sideEffect) builder.sideEffect();
    result_.model.sideEffect.push_back(sideEffect);
  }

  // A random resource not yet used by this node satisfying `ok`, or -1.
  template <typename Pred>
  int pickResource(const std::vector<uint32_t>& used, Pred ok) {
    std::vector<uint32_t> candidates;
    for (uint32_t r = 0; r < resources_.size(); ++r) {
      if (std::find(used.begin(), used.end(), r) == used.end() && ok(resources_[r])) candidates.push_back(r);
    }
    if (candidates.empty()) return -1;
    return static_cast<int>(candidates[below(static_cast<uint32_t>(candidates.size()))]);
  }

  Access readAccess(NodeType type, const ResourceState& state) {
    if (type == NodeType::Transfer) return Access::TransferSrc;
    if (state.kind == ResourceKind::Buffer) {
      static constexpr Access kGraphics[] = {Access::Vertex, Access::Index, Access::Indirect, Access::Uniform,
                                             Access::StorageRead};
      static constexpr Access kCompute[] = {Access::Uniform, Access::StorageRead, Access::Indirect};
      return type == NodeType::Graphics ? kGraphics[below(5)] : kCompute[below(3)];
    }
    if (state.depth && type == NodeType::Graphics && below(2) == 0) return Access::DepthAttachmentRead;
    return below(3) == 0 ? Access::StorageRead : Access::Sampled;
  }

  Access writeAccess(NodeType type, const ResourceState& state, bool canRead) {
    if (type == NodeType::Transfer) return Access::TransferDst;
    const bool readWrite = canRead && below(3) == 0;
    if (state.kind == ResourceKind::Texture && type == NodeType::Graphics && below(4) != 0) {
      if (state.depth) return readWrite ? Access::DepthAttachmentReadWrite : Access::DepthAttachmentWrite;
      if (!readWrite && below(6) == 0) return Access::ResolveDst;
      return readWrite ? Access::ColorAttachmentReadWrite : Access::ColorAttachmentWrite;
    }
    return readWrite ? Access::StorageReadWrite : Access::StorageWrite;
  }

  static bool readable(const ResourceState& state) { return state.imported || state.versions.size() > 1; }

  void addRead(NodeBuilder& builder, uint32_t node, NodeType type, std::vector<uint32_t>& used) {
    const int picked = pickResource(used, [](const ResourceState& s) { return readable(s); });
    if (picked < 0) return;
    const auto r = static_cast<uint32_t>(picked);
    ResourceState& state = resources_[r];
    const auto latest = static_cast<uint32_t>(state.versions.size() - 1);
    const uint32_t oldest = state.imported ? 0 : 1;
    uint32_t position = latest;
    if (latest > oldest && chance(params_.oldVersionReadChance)) position = oldest + below(latest - oldest);
    const Access access = readAccess(type, state);
    const uint32_t handle = state.versions[position];
    if (state.kind == ResourceKind::Texture) builder.read(TextureHandle{handle}, access);
    else builder.read(BufferHandle{handle}, access);
    used.push_back(r);
    result_.model.uses.push_back({.node = node, .resource = r, .readPos = static_cast<int>(position),
                                  .access = access});
  }

  void addWrite(NodeBuilder& builder, uint32_t node, NodeType type, std::vector<uint32_t>& used) {
    const int picked = pickResource(used, [](const ResourceState&) { return true; });
    if (picked < 0) return;
    const auto r = static_cast<uint32_t>(picked);
    ResourceState& state = resources_[r];
    const Access access = writeAccess(type, state, readable(state));
    const uint32_t latest = state.versions.back();
    const uint32_t produced = state.kind == ResourceKind::Texture
                                  ? builder.write(TextureHandle{latest}, access).version
                                  : builder.write(BufferHandle{latest}, access).version;
    const auto position = static_cast<int>(state.versions.size());
    const bool reads = accessInfo(access, type).reads;
    state.versions.push_back(produced);
    used.push_back(r);
    result_.model.uses.push_back({.node = node, .resource = r, .readPos = reads ? position - 1 : kNoPosition,
                                  .writePos = position, .access = access});
  }

  std::mt19937 rng_;
  RandomGraphParams params_;
  RandomGraph result_;
  std::vector<ResourceState> resources_;
};

}  // namespace

RandomGraph makeRandomGraph(uint32_t seed, const RandomGraphParams& params) {
  return Generator(seed, params).run();
}

CompileOptions randomCompileOptions(uint32_t queueCount) {
  CompileOptions options;
  options.queueCount = queueCount;
  options.queueOfClass = queueOfClassFor(queueCount);
  options.requirements = [](const ResourceDecl& decl, const ResolvedResource& resolved) {
    MemoryRequirements requirements = estimateRequirements(decl, resolved);
    const size_t hash = std::hash<std::string_view>{}(decl.name);
    requirements.alignment = hash % 3 == 0 ? 4096 : 256;
    if (decl.kind == ResourceKind::Buffer) requirements.memoryTypeBits = 0b0011;
    else requirements.memoryTypeBits = hash % 2 == 0 ? 0b0110 : 0b0100;
    return requirements;
  };
  return options;
}

}  // namespace fgb::graph::test
