#include "mesh_feature.hpp"

#include "../context/handles.hpp"

#include <fgb/rhi/job_context.hpp>
#include <fgb/scene/frustum.hpp>

#include <cstring>

namespace fgb::features {
namespace {

using graph::Access;
using graph::kStageFragmentShader;
using graph::kStageVertexShader;

struct CullPush {
  glm::vec4 planes[6];
  uint32_t instances;
  uint32_t commands;
  uint32_t visible;
  uint32_t stats;
  uint32_t instanceCount;
};
static_assert(sizeof(CullPush) <= rhi::kPushConstantBytes);

// Mirrors shaders/renderer/include/forward_push.glsl.
struct ForwardPush {
  uint32_t frame;
  uint32_t instances;
  uint32_t visible;
  uint32_t materials;
  uint32_t lights;
  uint32_t clusterCounts;
  uint32_t clusterIndices;
  uint32_t materialSampler;
  uint32_t flags;
};

constexpr uint32_t kStatsBytes = 16;
constexpr uint32_t kCommandStride = sizeof(DrawIndexedCommand);

rhi::GraphicsPipelineDesc forwardPipeline(const RenderSettings& settings, bool transparent) {
  rhi::GraphicsPipelineDesc desc;
  desc.name = transparent ? "mesh forward (blend)" : "mesh forward";
  desc.vertexShader = "renderer/forward.vert";
  desc.fragmentShader = "renderer/forward.frag";
  desc.vertexBindings = {{0, 12, false}, {1, 12, false}, {2, 16, false}, {3, 8, false}};
  desc.vertexAttributes = {{0, 0, rhi::VertexFormat::R32G32B32Sfloat, 0},
                           {1, 1, rhi::VertexFormat::R32G32B32Sfloat, 0},
                           {2, 2, rhi::VertexFormat::R32G32B32A32Sfloat, 0},
                           {3, 3, rhi::VertexFormat::R32G32Sfloat, 0}};
  // Winding is not relied on: imported models mix conventions and many materials are double-sided.
  desc.cullMode = rhi::CullMode::None;
  desc.colorFormats = {kHdrFormat};
  desc.blend = {transparent ? rhi::BlendMode::Alpha : rhi::BlendMode::Opaque};
  desc.depthFormat = kDepthFormat;
  desc.depthTest = true;
  desc.depthWrite = !transparent;
  desc.depthCompare = rhi::CompareOp::LessOrEqual;
  desc.samples = settings.msaa;
  return desc;
}

rhi::GraphicsPipelineDesc depthOnlyPipeline(const RenderSettings& settings) {
  rhi::GraphicsPipelineDesc desc = forwardPipeline(settings, false);
  desc.name = "mesh depth prepass";
  desc.fragmentShader.clear();
  desc.colorFormats.clear();
  desc.blend.clear();
  return desc;
}

// Binds the scene's vertex streams and indices and draws `groupCount` indirect commands.
void drawGroups(rhi::JobContext& ctx, const GpuScene& scene, graph::BufferHandle commands, uint32_t firstGroup,
                uint32_t groupCount) {
  auto& cmd = ctx.cmd();
  cmd.bindVertexBuffer(0, scene.vertices, scene.streams.positions);
  cmd.bindVertexBuffer(1, scene.vertices, scene.streams.normals);
  cmd.bindVertexBuffer(2, scene.vertices, scene.streams.tangents);
  cmd.bindVertexBuffer(3, scene.vertices, scene.streams.uvs);
  cmd.bindIndexBuffer(scene.indices, 0, rhi::IndexType::Uint32);
  cmd.drawIndexedIndirect(ctx.buffer(commands), uint64_t{firstGroup} * kCommandStride, groupCount, kCommandStride);
}

}  // namespace

void MeshFeature::configure(const GpuScene& scene) {
  scene_ = &scene;
  instanceCount_ = scene.instanceCount;
  hasTransparent_ = scene.groupRange(DrawClass::Transparent).second > 0;
}

void MeshFeature::initialize(FeatureInit& init) {
  configure(init.scene);
  device_ = &init.device;
  if (!enabled()) return;
  pipelines_.cull = init.device.createComputePipeline({"mesh frustum cull", "renderer/mesh_cull.comp"});
  pipelines_.opaque = init.device.createGraphicsPipeline(forwardPipeline(init.settings, false));
  depthPrepass_ = init.settings.depthPrepass;
  if (depthPrepass_) pipelines_.depthOnly = init.device.createGraphicsPipeline(depthOnlyPipeline(init.settings));
  if (hasTransparent_) pipelines_.transparent = init.device.createGraphicsPipeline(forwardPipeline(init.settings, true));
  statsReadback_ = init.device.createBuffer(
      {"mesh cull stats readback", kStatsBytes, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  std::memset(init.device.mapped(statsReadback_).data(), 0, kStatsBytes);
}

void MeshFeature::declareCull(graph::FrameGraph& graph, graph::BufferHandle& commands, graph::BufferHandle& visible,
                              graph::BufferHandle& stats) {
  const GpuScene& scene = *scene_;
  const auto commandBytes = uint64_t{kCommandStride} * scene.groups.size();
  commands = graph.createBuffer("mesh draw commands", {commandBytes, {}});
  visible = graph.createBuffer("visible instances", {uint64_t{4} * scene.instanceCount, {}});
  stats = graph.createBuffer("mesh cull stats", {kStatsBytes, {}});

  // Reset in its own node: the template's instance counts are 0, stats are zero-filled.
  auto reset = graph.addNode("Mesh Cull Reset", graph::NodeType::Transfer);
  commands = reset.write(commands, Access::TransferDst);
  stats = reset.write(stats, Access::TransferDst);
  reset.setJob([templ = scene.commandTemplate, commands, stats, commandBytes](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().copyBuffer(templ, ctx.buffer(commands), commandBytes);
    ctx.cmd().fillBuffer(ctx.buffer(stats), 0, kStatsBytes, 0);
  });

  auto cull = graph.addNode("Mesh Frustum Cull", graph::NodeType::Compute);
  commands = cull.write(commands, Access::StorageReadWrite);
  visible = cull.write(visible, Access::StorageWrite);
  stats = cull.write(stats, Access::StorageReadWrite);
  CullPush push{};
  const auto frustum = scene::Frustum::fromMatrix(scene.constants.viewProj);
  for (size_t i = 0; i < 6; ++i) push.planes[i] = frustum.planes[i];
  push.instances = device_->storageBufferIndex(scene.instances);
  push.instanceCount = scene.instanceCount;
  cull.setJob([push, pipeline = pipelines_.cull, commands, visible, stats](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.commands = ctx.storageBufferIndex(commands);
    push.visible = ctx.storageBufferIndex(visible);
    push.stats = ctx.storageBufferIndex(stats);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().dispatch((push.instanceCount + 63) / 64);
  });
}

void MeshFeature::declareStatsReadback(graph::FrameGraph& graph, graph::BufferHandle stats) {
  const graph::ImportState hostState{graph::kStageHost | graph::kStageTransfer,
                                     graph::kAccessHostRead | graph::kAccessTransferWrite, graph::Layout::Undefined,
                                     graph::QueueClass::Graphics};
  auto target = graph.importBuffer("mesh cull stats readback", {kStatsBytes, {}}, rhi::external(statsReadback_),
                                   hostState, hostState);
  auto node = graph.addNode("Mesh Stats Readback", graph::NodeType::Transfer);
  node.read(stats, Access::TransferSrc);
  target = node.write(target, Access::TransferDst);
  node.sideEffect();
  node.setJob([stats, target](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().copyBuffer(ctx.buffer(stats), ctx.buffer(target), kStatsBytes);
  });
}

void MeshFeature::declareDraw(graph::FrameGraph& graph, Blackboard& board, DrawClass firstClass, DrawClass lastClass,
                              std::string_view nodeName, graph::BufferHandle commands, graph::BufferHandle visible) {
  const GpuScene& scene = *scene_;
  const uint32_t firstGroup = scene.groupRange(firstClass).first;
  const auto [lastFirst, lastCount] = scene.groupRange(lastClass);
  const uint32_t groupCount = lastFirst + lastCount - firstGroup;
  const bool transparent = firstClass == DrawClass::Transparent;

  auto node = addForwardPass(graph, board.get<FrameTargets>(), nodeName, !transparent);
  node.read(commands, Access::Indirect);
  // Storage buffers are visible per descriptor binding, not per stage: both forward shaders read
  // through the read-only binding, so every buffer this node reads is declared for both stages
  // (synchronization validation checks each read against the stages the barriers cover).
  constexpr graph::StageMask kForwardStages = kStageVertexShader | kStageFragmentShader;
  node.read(visible, Access::StorageRead, kForwardStages);
  ForwardPush push{};
  push.frame = device_->storageBufferIndex(scene.frameConstants);
  push.instances = device_->storageBufferIndex(scene.instances);
  push.materials = device_->storageBufferIndex(scene.materials);
  push.lights = device_->storageBufferIndex(scene.lights);
  push.clusterCounts = push.clusterIndices = rhi::kInvalidId;
  push.materialSampler = device_->samplerIndex(scene.materialSampler);
  push.flags = transparent ? 2u : 0u;
  ClusteredLights clusters;
  if (const auto* published = board.find<ClusteredLights>()) {
    clusters = *published;
    node.read(clusters.counts, Access::StorageRead, kForwardStages);
    node.read(clusters.indices, Access::StorageRead, kForwardStages);
  }
  const rhi::PipelineId pipeline = transparent ? pipelines_.transparent : pipelines_.opaque;
  node.setJob([push, pipeline, clusters, commands, visible, firstGroup, groupCount, &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    push.visible = ctx.storageBufferIndex(visible);
    if (clusters.counts.valid()) {
      push.clusterCounts = ctx.storageBufferIndex(clusters.counts);
      push.clusterIndices = ctx.storageBufferIndex(clusters.indices);
    }
    cmd.bindPipeline(pipeline);
    cmd.push(push);
    drawGroups(ctx, scene, commands, firstGroup, groupCount);
  });
}

void MeshFeature::declareDepthPrepass(graph::FrameGraph& graph, Blackboard& board, graph::BufferHandle commands,
                                      graph::BufferHandle visible) {
  const GpuScene& scene = *scene_;
  auto& targets = board.get<FrameTargets>();
  auto node = graph.addNode("Depth Prepass", graph::NodeType::Graphics);
  node.read(commands, graph::Access::Indirect);
  node.read(visible, graph::Access::StorageRead, kStageVertexShader);
  targets.depth = node.setDepthStencil(targets.depth, graph::LoadOp::Clear);
  targets.depthCleared = true;
  ForwardPush push{};
  push.frame = device_->storageBufferIndex(scene.frameConstants);
  push.instances = device_->storageBufferIndex(scene.instances);
  const auto [firstGroup, groupCount] = scene.groupRange(DrawClass::Opaque);
  node.setJob([push, pipeline = pipelines_.depthOnly, commands, visible, first = firstGroup, count = groupCount,
               &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.visible = ctx.storageBufferIndex(visible);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    drawGroups(ctx, scene, commands, first, count);
  });
}

void MeshFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  graph::BufferHandle commands, visible, stats;
  declareCull(graph, commands, visible, stats);
  declareStatsReadback(graph, stats);
  if (depthPrepass_) declareDepthPrepass(graph, board, commands, visible);
  declareDraw(graph, board, DrawClass::Opaque, DrawClass::Masked, "Mesh Render", commands, visible);
  if (hasTransparent_)
    declareDraw(graph, board, DrawClass::Transparent, DrawClass::Transparent, "Mesh Render Transparent", commands,
                visible);
}

void MeshFeature::addStats(std::map<std::string, double>& stats) const {
  MeshCullStats read{};
  if (enabled()) std::memcpy(&read, device_->mapped(statsReadback_).data(), sizeof(read));
  stats["instances_visible"] = read.instancesVisible;
  stats["triangles_visible"] = read.trianglesVisible;
}

}  // namespace fgb::features
