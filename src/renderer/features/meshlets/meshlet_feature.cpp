#include "meshlet_feature.hpp"

#include <cstring>
#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>

#include "../context/handles.hpp"
#include "renderer/shared/meshlets.h"

namespace fgb::features {
namespace {

using graph::Access;

constexpr uint64_t kStatsBytes = sizeof(gpu::MeshletStats);
constexpr uint32_t kCommandStride = sizeof(gpu::MeshletTaskCommand);
// Every buffer "Meshlet Render" reads or writes is reached through bindings all three of its
// stages use, so synchronization validation counts each as accessed by all three (as forward's
// "Mesh Render" declares its reads for both of its stages).
constexpr graph::StageMask kRenderStages =
    graph::kStageTaskShader | graph::kStageMeshShader | graph::kStageFragmentShader;

rhi::GraphicsPipelineDesc meshletPipeline(const RenderSettings& settings) {
  rhi::GraphicsPipelineDesc desc;
  desc.name = "meshlet forward";
  desc.taskShader = "renderer/meshlets/meshlet.task";
  desc.meshShader = "renderer/meshlets/meshlet.mesh";
  desc.fragmentShader = "renderer/forward.frag";
  // As forward's "Mesh Render": the mesh shader culls back faces of single-sided materials itself.
  desc.cullMode = rhi::CullMode::None;
  desc.colorFormats = {kHdrFormat};
  desc.blend = {rhi::BlendMode::Opaque};
  setDepthState(desc, DepthTest::Attachment, true);
  desc.samples = settings.msaa;
  return desc;
}

}  // namespace

void MeshletFeature::initialize(FeatureInit& init) {
  device_ = &init.device;
  scene_ = &init.scene;
  drawCount_ = init.scene.clusterGeometry.drawCount;  // the path uploads the clusters (upload.clusters)
  if (!enabled()) return;
  if (!init.device.meshShaders())
    throw InputError("render.path=" + init.path.source + " needs VK_EXT_mesh_shader (task and mesh shaders), which " +
                     init.device.adapter().name + " lacks");
  // render.lod_error is in output pixels; the scene passes have render.ssaa times as many.
  lodThreshold_ = lod_ ? init.settings.lodError * float(init.settings.ssaa) : 0.0f;
  // The small-triangle test knows the sample positions only where they are the standard ones.
  const uint32_t samples = init.settings.msaa;
  const bool smallTriangles = samples == 1 || init.device.standardSampleLocations();
  meshFlags_ = (smallTriangles ? gpu::kMeshletSmallTriangles : 0u) | samples << gpu::kMeshletSamplesShift;
  injectNan_ = init.settings.injectNanPass == "Meshlet Render";
  cull_ = init.device.createComputePipeline({"meshlet instance cull", "renderer/meshlets/meshlet_instance_cull.comp"});
  render_ = init.device.createGraphicsPipeline(meshletPipeline(init.settings));
  statsReadback_ = createReadbackBuffer(init.device, "meshlet stats readback", kStatsBytes);
}

void MeshletFeature::declareReset(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Meshlet Reset", graph::NodeType::Transfer);
  b.commands = node.write(b.commands, Access::TransferDst);
  b.stats = node.write(b.stats, Access::TransferDst);
  node.setJob([b](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().fillBuffer(ctx.buffer(b.commands), 0, FGB_MESHLET_COMMANDS_OFFSET, 0);  // the draw count
    ctx.cmd().fillBuffer(ctx.buffer(b.stats), 0, kStatsBytes, 0);
  });
  node.recordingFixed();
}

void MeshletFeature::declareInstanceCull(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Meshlet Instance Cull", graph::NodeType::Compute);
  b.commands = node.write(b.commands, Access::StorageReadWrite);
  b.stats = node.write(b.stats, Access::StorageReadWrite);
  gpu::MeshletCullPush push{};
  push.ranges = device_->storageBufferIndex(scene_->clusterGeometry.instanceDraws);
  push.instanceCount = scene_->instanceCount;
  node.setJob([push, pipeline = cull_, b, scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    const FrameBuffers& frame = scene->frame(ctx.execution());
    push.frame = frame.constantsIndex;  // the frustum planes
    push.instances = frame.instancesIndex;
    push.commands = ctx.storageBufferIndex(b.commands);
    push.stats = ctx.storageBufferIndex(b.stats);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().dispatch((push.instanceCount + FGB_MESHLET_CULL_GROUP_SIZE - 1) / FGB_MESHLET_CULL_GROUP_SIZE);
  });
  node.recordingFixed();
}

void MeshletFeature::declareRender(graph::FrameGraph& graph, Blackboard& board, Buffers& b) const {
  const GpuScene& scene = *scene_;
  const ClusterGeometry& geometry = scene.clusterGeometry;
  auto& targets = board.get<FrameTargets>();
  auto node = addForwardPass(graph, targets, "Meshlet Render", true, DepthTest::Attachment);
  node.read(b.commands, Access::Indirect);
  node.read(b.commands, Access::StorageRead, kRenderStages);
  b.stats = node.write(b.stats, Access::StorageReadWrite, kRenderStages);
  if (targets.exposure.valid()) node.read(targets.exposure, Access::StorageRead, kRenderStages);
  gpu::MeshletPush push{};
  push.shading.materials = device_->storageBufferIndex(scene.materials);
  push.shading.clusterCounts = push.shading.clusterIndices = rhi::kInvalidId;
  push.shading.materialSampler = device_->samplerIndex(scene.materialSampler);
  push.shading.flags = injectNan_ ? gpu::kForwardInjectNan : 0u;
  push.shading.opaqueDepth = {FGB_NONE, 0, 0};  // the depth attachment tests (DepthTest::Attachment)
  push.draws = device_->storageBufferIndex(geometry.draws);
  push.clusters = device_->storageBufferIndex(geometry.clusters);
  push.triangles = device_->storageBufferIndex(geometry.packedTriangles);
  push.positions = device_->storageBufferIndex(geometry.vertices);
  push.vertices = device_->storageBufferIndex(scene.vertices);
  push.normals = uint32_t(scene.streams.normals / sizeof(float));
  push.tangents = uint32_t(scene.streams.tangents / sizeof(float));
  push.uvs = uint32_t(scene.streams.uvs / sizeof(float));
  push.ranges = device_->storageBufferIndex(geometry.instanceDraws);
  push.flags = meshFlags_;
  push.lodThreshold = lodThreshold_;
  ClusteredLights clusters;
  if (const auto* published = board.find<ClusteredLights>()) {
    clusters = *published;
    node.read(clusters.counts, Access::StorageRead, kRenderStages);
    node.read(clusters.indices, Access::StorageRead, kRenderStages);
  }
  node.setJob([push, pipeline = render_, b, clusters, maxDraws = scene.instanceCount,
               scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    const FrameBuffers& frame = scene->frame(ctx.execution());
    push.shading.frame = frame.constantsIndex;
    push.shading.instances = frame.instancesIndex;
    push.shading.lights = frame.lightsIndex;
    if (clusters.counts.valid()) {
      push.shading.clusterCounts = ctx.storageBufferIndex(clusters.counts);
      push.shading.clusterIndices = ctx.storageBufferIndex(clusters.indices);
    }
    push.commands = ctx.storageBufferIndex(b.commands);
    push.stats = ctx.storageBufferIndex(b.stats);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().drawMeshTasksIndirectCount(ctx.buffer(b.commands), FGB_MESHLET_COMMANDS_OFFSET, ctx.buffer(b.commands), 0,
                                         maxDraws, kCommandStride);
  });
  node.recordingFixed();
}

void MeshletFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  Buffers b;
  const uint64_t commandBytes = FGB_MESHLET_COMMANDS_OFFSET + uint64_t{kCommandStride} * scene_->instanceCount;
  b.commands = graph.createBuffer("meshlet task draws", {commandBytes, {}});
  b.stats = graph.createBuffer("meshlet stats", {kStatsBytes, {}});
  declareReset(graph, b);
  declareInstanceCull(graph, b);
  declareRender(graph, board, b);
  declareReadback(graph, "Meshlet Stats Readback", b.stats, statsReadback_, "meshlet stats readback", kStatsBytes);
}

void MeshletFeature::addStats(std::map<std::string, double>& stats) const {
  if (!enabled()) return;
  gpu::MeshletStats read{};
  std::memcpy(&read, device_->mapped(statsReadback_).data(), sizeof(read));
  stats["meshlet_clusters"] = drawCount_;
  stats["meshlet_instances_visible"] = read.instancesVisible;
  stats["meshlet_clusters_visible"] = read.clustersVisible;
  stats["meshlet_triangles_tested"] = read.trianglesTested;
  stats["meshlet_triangles_rasterised"] = read.trianglesRasterised;
  stats["meshlet_lod_threshold_px"] = lodThreshold_;
  stats["meshlet_small_triangle_culling"] = (meshFlags_ & gpu::kMeshletSmallTriangles) != 0 ? 1.0 : 0.0;
}

}  // namespace fgb::features
