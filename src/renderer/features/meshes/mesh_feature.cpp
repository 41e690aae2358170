#include "mesh_feature.hpp"

#include "../context/handles.hpp"
#include "renderer/shared/meshes.h"

#include <fgb/rhi/job_context.hpp>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace fgb::features {
namespace {

using graph::Access;
using graph::kStageFragmentShader;
using graph::kStageVertexShader;

constexpr uint32_t kBatchCount = FGB_MESH_BATCH_COUNT;  // one per DrawClass
constexpr uint32_t kStatsBytes = sizeof(MeshCullStats);
constexpr uint32_t kCommandStride = sizeof(gpu::DrawCommand);
constexpr uint32_t kChunk = FGB_TRANSPARENT_CHUNK_SIZE;
// "Transparent Cluster Cull" dispatches its chunks as (min(n, W), ceil(n / W)) workgroups.
constexpr uint32_t kMaxGroupsX = 65535;
// Storage buffers are visible per descriptor binding, not per stage: both forward shaders read
// through the read-only binding, so every buffer a forward pass reads is declared for both stages
// (synchronization validation checks each read against the stages the barriers cover).
constexpr graph::StageMask kForwardStages = kStageVertexShader | kStageFragmentShader;

// Opaque and masked instances write depth; transparent ones only test it (forward: against the
// depth attachment; visibility buffer: against the opaque depth buffer, in forward.frag).
rhi::GraphicsPipelineDesc forwardPipeline(const RenderSettings& settings, bool transparent, DepthTest transparentTest) {
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
  setDepthState(desc, transparent ? transparentTest : DepthTest::Attachment, !transparent);
  desc.samples = settings.msaa;
  return desc;
}

rhi::GraphicsPipelineDesc depthOnlyPipeline(const RenderSettings& settings) {
  rhi::GraphicsPipelineDesc desc = forwardPipeline(settings, false, DepthTest::Attachment);
  desc.name = "mesh depth prepass";
  desc.fragmentShader.clear();
  desc.colorFormats.clear();
  desc.blend.clear();
  return desc;
}

// The draw groups of one draw class: one multi-draw.
struct Batch {
  uint32_t drawClass = 0;
  uint32_t firstGroup = 0;
  uint32_t groupCount = 0;
};

std::vector<Batch> batchesOf(const GpuScene& scene, const std::vector<DrawClass>& classes) {
  std::vector<Batch> batches;
  for (const DrawClass drawClass : classes) {
    const auto [first, count] = scene.groupRange(drawClass);
    if (count > 0) batches.push_back({static_cast<uint32_t>(drawClass), first, count});
  }
  return batches;
}

// The scene's vertex streams (forwardPipeline's bindings) and an index buffer.
void bindGeometry(rhi::CommandBuffer& cmd, const GpuScene& scene, rhi::BufferId indices) {
  cmd.bindVertexBuffer(0, scene.vertices, scene.streams.positions);
  cmd.bindVertexBuffer(1, scene.vertices, scene.streams.normals);
  cmd.bindVertexBuffer(2, scene.vertices, scene.streams.tangents);
  cmd.bindVertexBuffer(3, scene.vertices, scene.streams.uvs);
  cmd.bindIndexBuffer(indices, 0, rhi::IndexType::Uint32);
}

// Binds the scene's geometry and issues one multi-draw per batch: with a count buffer, the packed
// commands of groups with visible instances; otherwise every group's command (culled groups have
// instance count 0).
void drawBatches(rhi::JobContext& ctx, const GpuScene& scene, const MeshCullOutputs& cull,
                 const std::vector<Batch>& batches, bool drawCount) {
  auto& cmd = ctx.cmd();
  bindGeometry(cmd, scene, scene.indices);
  for (const Batch& batch : batches) {
    const uint64_t offset = uint64_t{batch.firstGroup} * kCommandStride;
    if (drawCount) {
      cmd.drawIndexedIndirectCount(ctx.buffer(cull.drawList), offset, ctx.buffer(cull.drawCounts),
                                   uint64_t{4} * batch.drawClass, batch.groupCount, kCommandStride);
    } else {
      cmd.drawIndexedIndirect(ctx.buffer(cull.commands), offset, batch.groupCount, kCommandStride);
    }
  }
}

// A forward pass's per-execution push values: the frame's copies, the light lists, the opaque depth.
void setFramePush(gpu::ForwardPush& push, rhi::JobContext& ctx, const GpuScene& scene, const ClusteredLights& clusters,
                  const OpaqueDepthSource& opaqueDepth) {
  useFrame(push, scene, ctx.execution());
  push.opaqueDepth = opaqueDepth.push(ctx);
  useLightLists(push, ctx, clusters);
}

// The indirect buffers a draw node reads.
void readDrawCommands(graph::NodeBuilder& node, const MeshCullOutputs& cull, bool drawCount) {
  if (drawCount) {
    node.read(cull.drawList, Access::Indirect);
    node.read(cull.drawCounts, Access::Indirect);
  } else {
    node.read(cull.commands, Access::Indirect);
  }
}

// render.transparent over the plan's option "transparent".
bool computesTransparent(TransparentDraw knob, bool plan) {
  return knob == TransparentDraw::Compute || (knob == TransparentDraw::Plan && plan);
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
  transparentDepthTest_ = init.path.depthTest;
  if (!enabled()) return;
  // At render.lod_error=0 the index range is full detail in the index buffer's triangle order: the
  // image without LOD.
  const TransparentClusters& clusters = init.scene.clusterGeometry.transparent;
  const bool clusterCut = lod_ && hasTransparent_ && clusters.maxEntries > 0;
  // The compute passes blend over the image "Material Shade" wrote and test its depth buffer: a
  // scene with nothing opaque (no Material Shade) rasters.
  computeTransparent_ = clusterCut && transparentDepthTest_ == DepthTest::OpaqueDepthBuffer &&
                        init.scene.clusterGeometry.drawCount > 0 &&
                        computesTransparent(init.settings.transparentDraw, planComputeTransparent_);
  transparentLod_ = clusterCut && (computeTransparent_ || init.settings.lodError > 0.0f);
  if (transparentLod_) {
    lodThreshold_ = init.settings.lodThresholdScenePixels();
    // One invocation per (transparent instance, cluster of the largest transparent mesh).
    const uint64_t invocations = uint64_t{clusters.maxEntries} * scene_->groupRange(DrawClass::Transparent).second;
    const uint64_t chunks = (invocations + kChunk - 1) / kChunk;
    if (chunks > uint64_t{kMaxGroupsX} * kMaxGroupsX || chunks * kChunk > UINT32_MAX)
      throw std::logic_error("transparent cluster draws exceed what one draw count and two dispatch dimensions hold");
    transparentChunks_ = uint32_t(chunks);
    pipelines_.transparentCull =
        init.device.createComputePipeline({"transparent cluster cull", "renderer/transparent_cluster_cull.comp"});
    pipelines_.transparentPack =
        init.device.createComputePipeline({"transparent cluster pack", "renderer/transparent_cluster_pack.comp"});
  }
  pipelines_.cull = init.device.createComputePipeline({"mesh frustum cull", "renderer/mesh_cull.comp"});
  drawCount_ = init.device.drawIndirectCount();
  if (drawCount_) pipelines_.compact = init.device.createComputePipeline({"mesh draw compaction", "renderer/mesh_compact.comp"});
  if (drawsOpaque_)
    pipelines_.opaque =
        init.device.createGraphicsPipeline(forwardPipeline(init.settings, false, DepthTest::Attachment));
  depthPrepass_ = drawsOpaque_ && init.settings.depthPrepass;
  injectNanPass_ = init.settings.injectNanPass;
  injectBiasPass_ = init.settings.injectBiasPass;
  if (depthPrepass_) pipelines_.depthOnly = init.device.createGraphicsPipeline(depthOnlyPipeline(init.settings));
  // A fragment id of the compute passes is (packed draw << 7) | triangle (kClusterTriangleBits).
  if (computeTransparent_ && uint64_t{transparentChunks_} * kChunk > (uint64_t{1} << 25))
    throw std::logic_error("transparent cluster draws exceed the compute fragment id's 25 draw bits");
  if (computeTransparent_)
    transparentCompute_.initialize(init);
  else if (hasTransparent_)
    pipelines_.transparent =
        init.device.createGraphicsPipeline(forwardPipeline(init.settings, true, transparentDepthTest_));
  statsReadback_ = createReadbackBuffer(init.device, "mesh cull stats readback", kStatsBytes);
}

MeshCullOutputs MeshFeature::declareCull(graph::FrameGraph& graph) {
  const GpuScene& scene = *scene_;
  const auto commandBytes = uint64_t{kCommandStride} * scene.groups.size();
  MeshCullOutputs out;
  out.commands = graph.createBuffer("mesh draw commands", {commandBytes, {}});
  out.visible = graph.createBuffer("visible instances", {uint64_t{4} * scene.instanceCount, {}});
  out.stats = graph.createBuffer("mesh cull stats", {kStatsBytes, {}});

  // Reset in its own node: the template's instance counts are 0, stats are zero-filled.
  auto reset = graph.addNode("Mesh Cull Reset", graph::NodeType::Transfer);
  out.commands = reset.write(out.commands, Access::TransferDst);
  out.stats = reset.write(out.stats, Access::TransferDst);
  reset.setJob([&scene, commands = out.commands, stats = out.stats, commandBytes](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    // This frame's template: the transparent groups' order is the frame's back-to-front order.
    ctx.cmd().copyBuffer(scene.frame(ctx.execution()).commandTemplate, ctx.buffer(commands), commandBytes);
    ctx.cmd().fillBuffer(ctx.buffer(stats), 0, kStatsBytes, 0);
  });
  reset.recordingFixed();

  auto cull = graph.addNode("Mesh Frustum Cull", graph::NodeType::Compute);
  out.commands = cull.write(out.commands, Access::StorageReadWrite);
  out.visible = cull.write(out.visible, Access::StorageWrite);
  out.stats = cull.write(out.stats, Access::StorageReadWrite);
  gpu::MeshCullPush push{};
  push.instanceCount = scene.instanceCount;
  push.firstTransparentGroup = scene.groupRange(DrawClass::Transparent).first;
  gpu::MeshCompactPush compact{};
  if (drawCount_) {
    out.drawList = cull.write(graph.createBuffer("mesh draw list", {commandBytes, {}}), Access::StorageWrite);
    out.drawCounts = cull.write(graph.createBuffer("mesh draw counts", {uint64_t{4} * kBatchCount, {}}),
                                Access::StorageWrite);
    for (uint32_t c = 0; c < kBatchCount; ++c) {
      const auto [first, count] = scene.groupRange(static_cast<DrawClass>(c));
      compact.batches[c] = {first, count, 0, 0};
    }
  }
  cull.setJob([push, compact, pipelines = pipelines_, out, &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    useFrame(push, scene, ctx.execution());  // the frustum planes, the instances
    push.commands = ctx.storageBufferIndex(out.commands);
    push.visible = ctx.storageBufferIndex(out.visible);
    push.stats = ctx.storageBufferIndex(out.stats);
    ctx.cmd().bindPipeline(pipelines.cull);
    ctx.cmd().push(push);
    ctx.cmd().dispatch((push.instanceCount + FGB_MESH_CULL_GROUP_SIZE - 1) / FGB_MESH_CULL_GROUP_SIZE);
    if (!out.drawList.valid()) return;
    // The packing reads the instance counts every cull workgroup added to.
    ctx.cmd().computeBarrier();
    compact.commands = push.commands;
    compact.drawList = ctx.storageBufferIndex(out.drawList);
    compact.drawCounts = ctx.storageBufferIndex(out.drawCounts);
    compact.stats = push.stats;
    ctx.cmd().bindPipeline(pipelines.compact);
    ctx.cmd().push(compact);
    ctx.cmd().dispatch(kBatchCount);
  });
  cull.recordingFixed();
  return out;
}

void MeshFeature::declareDraw(graph::FrameGraph& graph, Blackboard& board, std::vector<DrawClass> classes,
                              std::string_view nodeName, const MeshCullOutputs& cull) {
  const GpuScene& scene = *scene_;
  const bool transparent = classes.front() == DrawClass::Transparent;
  const DepthTest depthTest = transparent ? transparentDepthTest_ : DepthTest::Attachment;
  auto& targets = board.get<FrameTargets>();
  auto node = addForwardPass(graph, targets, nodeName, !transparent, depthTest);
  readDrawCommands(node, cull, drawCount_);
  node.read(cull.visible, Access::StorageRead, kForwardStages);
  const ClusteredLights clusters = readLightLists(node, board, kForwardStages);
  const rhi::PipelineId pipeline = transparent ? pipelines_.transparent : pipelines_.opaque;
  node.setJob([push = forwardPush(nodeName, transparent), pipeline, clusters, cull, batches = batchesOf(scene, classes),
               drawCount = drawCount_, opaqueDepth = opaqueDepthSource(targets, depthTest),
               &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    setFramePush(push, ctx, scene, clusters, opaqueDepth);
    push.visible = ctx.storageBufferIndex(cull.visible);
    cmd.bindPipeline(pipeline);
    cmd.push(push);
    drawBatches(ctx, scene, cull, batches, drawCount);
  });
  node.recordingFixed();
}

gpu::ForwardPush MeshFeature::forwardPush(std::string_view nodeName, bool transparent) const {
  gpu::ForwardPush push{};
  push.materials = device_->storageBufferIndex(scene_->materials);
  push.clusterCounts = push.clusterIndices = rhi::kInvalidId;
  push.materialSampler = device_->samplerIndex(scene_->materialSampler);
  push.flags = (transparent ? gpu::kForwardTransparent : 0u) |
               (nodeName == injectNanPass_ ? gpu::kForwardInjectNan : 0u) |
               (nodeName == injectBiasPass_ ? gpu::kForwardInjectBias : 0u);
  return push;
}

// The transparent instances' LOD cut, per instance in the frame's back-to-front order (the command
// template's transparent groups: one instance each, GPU instances firstSlot...). Two dispatches:
// the cut and frustum tests write each chunk's kept draws in order (transparent_cluster_cull.comp),
// then every chunk's draws are packed after the chunks before it (transparent_cluster_pack.comp).
TransparentClusterDraws MeshFeature::declareTransparentCull(graph::FrameGraph& graph, MeshCullOutputs& cull) const {
  const GpuScene& scene = *scene_;
  const auto [firstGroup, slotCount] = scene.groupRange(DrawClass::Transparent);
  const uint64_t draws = uint64_t{transparentChunks_} * kChunk;
  TransparentClusterDraws out;
  auto node = graph.addNode("Transparent Cluster Cull", graph::NodeType::Compute);
  // Written whole by the first dispatch; the packing reads them after a barrier in the node.
  out.chunkCommands =
      node.write(graph.createBuffer("transparent chunk draws", {draws * kCommandStride, {}}), Access::StorageWrite);
  out.chunkTotals = node.write(graph.createBuffer("transparent chunk totals", {uint64_t{16} * transparentChunks_, {}}),
                               Access::StorageWrite);
  out.packed =
      node.write(graph.createBuffer("transparent cluster draws", {draws * kCommandStride, {}}), Access::StorageWrite);
  out.drawCount = node.write(graph.createBuffer("transparent cluster draw count", {4, {}}), Access::StorageWrite);
  cull.stats = node.write(cull.stats, Access::StorageReadWrite);  // its transparent cluster words
  if (computeTransparent_)
    out.dispatchArgs = node.write(graph.createBuffer("transparent raster dispatch", {12, {}}), Access::StorageWrite);
  const TransparentClusters& clusters = scene.clusterGeometry.transparent;
  gpu::TransparentCullPush push{};
  push.clusters = device_->storageBufferIndex(scene.clusterGeometry.clusters);
  push.meshes = device_->storageBufferIndex(clusters.meshes);
  push.entries = device_->storageBufferIndex(clusters.entries);
  push.firstSlot = scene.groups[firstGroup].firstSlot;
  push.slotCount = slotCount;
  push.entryStride = clusters.maxEntries;
  push.chunkCount = transparentChunks_;
  push.lodThreshold = lodThreshold_;
  push.flags = computeTransparent_ ? gpu::kTransparentCullClusterIds : 0u;
  node.setJob([push, pipelines = pipelines_, out, stats = cull.stats, &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, scene, ctx.execution());
    push.chunkCommands = ctx.storageBufferIndex(out.chunkCommands);
    push.chunkTotals = ctx.storageBufferIndex(out.chunkTotals);
    push.packed = ctx.storageBufferIndex(out.packed);
    push.drawCount = ctx.storageBufferIndex(out.drawCount);
    push.stats = ctx.storageBufferIndex(stats);
    push.dispatchArgs = out.dispatchArgs.valid() ? ctx.storageBufferIndex(out.dispatchArgs) : FGB_NONE;
    const uint32_t groupsX = std::min(push.chunkCount, kMaxGroupsX);
    const uint32_t groupsY = (push.chunkCount + groupsX - 1) / groupsX;
    cmd.bindPipeline(pipelines.transparentCull);
    cmd.push(push);
    cmd.dispatch(groupsX, groupsY);
    cmd.computeBarrier();  // the packing reads every chunk's draws and totals
    cmd.bindPipeline(pipelines.transparentPack);
    cmd.push(push);
    cmd.dispatch(groupsX, groupsY);
  });
  node.recordingFixed();
  return out;
}

// "Mesh Render Transparent" from the LOD cut's cluster draws: with a count buffer the packed
// draws, otherwise every chunk's draws (the tail of each chunk zero draws).
void MeshFeature::declareTransparentClusterDraw(graph::FrameGraph& graph, Blackboard& board,
                                                const TransparentClusterDraws& draws) {
  const GpuScene& scene = *scene_;
  auto& targets = board.get<FrameTargets>();
  const std::string_view nodeName = "Mesh Render Transparent";
  auto node = addForwardPass(graph, targets, nodeName, false, transparentDepthTest_);
  if (drawCount_) {
    node.read(draws.packed, Access::Indirect);
    node.read(draws.drawCount, Access::Indirect);
  } else {
    node.read(draws.chunkCommands, Access::Indirect);
  }
  const ClusteredLights clusters = readLightLists(node, board, kForwardStages);
  gpu::ForwardPush push = forwardPush(nodeName, true);
  push.flags |= gpu::kForwardInstanceIsSlot;
  push.visible = rhi::kInvalidId;
  node.setJob([push, pipeline = pipelines_.transparent, clusters, draws, drawCount = drawCount_,
               maxDraws = transparentChunks_ * kChunk, opaqueDepth = opaqueDepthSource(targets, transparentDepthTest_),
               &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    setFramePush(push, ctx, scene, clusters, opaqueDepth);
    cmd.bindPipeline(pipeline);
    cmd.push(push);
    bindGeometry(cmd, scene, scene.clusterGeometry.transparent.indices);
    if (drawCount)
      cmd.drawIndexedIndirectCount(ctx.buffer(draws.packed), 0, ctx.buffer(draws.drawCount), 0, maxDraws,
                                   kCommandStride);
    else
      cmd.drawIndexedIndirect(ctx.buffer(draws.chunkCommands), 0, maxDraws, kCommandStride);
  });
  node.recordingFixed();
}

void MeshFeature::declareDepthPrepass(graph::FrameGraph& graph, Blackboard& board, const MeshCullOutputs& cull) {
  const GpuScene& scene = *scene_;
  auto& targets = board.get<FrameTargets>();
  auto node = graph.addNode("Depth Prepass", graph::NodeType::Graphics);
  readDrawCommands(node, cull, drawCount_);
  node.read(cull.visible, graph::Access::StorageRead, kStageVertexShader);
  targets.depth = node.setDepthStencil(targets.depth, graph::LoadOp::Clear, graph::ClearValue{{}, kDepthClear, 0});
  targets.depthCleared = true;
  gpu::ForwardPush push{};
  node.setJob([push, pipeline = pipelines_.depthOnly, cull, batches = batchesOf(scene, {DrawClass::Opaque}),
               drawCount = drawCount_, &scene](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    useFrame(push, scene, ctx.execution());
    push.visible = ctx.storageBufferIndex(cull.visible);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    drawBatches(ctx, scene, cull, batches, drawCount);
  });
  node.recordingFixed();
}

void MeshFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  MeshCullOutputs cull = declareCull(graph);
  TransparentClusterDraws clusterDraws;
  if (transparentLod_) clusterDraws = declareTransparentCull(graph, cull);
  declareReadback(graph, "Mesh Stats Readback", cull.stats, statsReadback_, "mesh cull stats readback", kStatsBytes);
  if (depthPrepass_) declareDepthPrepass(graph, board, cull);
  if (drawsOpaque_) declareDraw(graph, board, {DrawClass::Opaque, DrawClass::Masked}, "Mesh Render", cull);
  if (computeTransparent_)
    transparentCompute_.declare(graph, board, clusterDraws.packed, clusterDraws.drawCount, clusterDraws.dispatchArgs);
  else if (transparentLod_)
    declareTransparentClusterDraw(graph, board, clusterDraws);
  else if (hasTransparent_)
    declareDraw(graph, board, {DrawClass::Transparent}, "Mesh Render Transparent", cull);
}

void MeshFeature::addStats(std::map<std::string, double>& stats) const {
  MeshCullStats read{};
  if (enabled()) std::memcpy(&read, device_->mapped(statsReadback_).data(), sizeof(read));
  stats["instances_visible"] = read.instancesVisible;
  stats["triangles_visible"] = read.trianglesVisible;
  if (drawCount_) stats["draws_issued"] = read.drawsIssued;
  // What "Mesh Render Transparent" drew: full detail, or (option "lod") the LOD cut's clusters.
  stats["transparent_triangles_drawn"] = transparentLod_ ? read.transparentClusterTriangles : read.transparentTriangles;
  if (!transparentLod_) return;
  stats["transparent_clusters_drawn"] = read.transparentClusters;
  stats["transparent_whole_meshes_drawn"] = read.transparentWholeMeshes;
  if (computeTransparent_) transparentCompute_.addStats(stats);
}

}  // namespace fgb::features
