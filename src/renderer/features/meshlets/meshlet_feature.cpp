#include "meshlet_feature.hpp"

#include <cstring>
#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>
#include <fgb/shaders/registry.hpp>

#include "../context/handles.hpp"
#include "../visbuffer/hiz_pyramid.hpp"
#include "renderer/shared/meshlets.h"
#include "renderer/shared/visbuffer.h"  // HizPush, the HiZ build shared with the visibility buffer

namespace fgb::features {
namespace {

using graph::Access;

constexpr uint64_t kStatsBytes = sizeof(gpu::MeshletStats);
// MeshletPush::occlusion packs two storage-buffer indices in 16 bits each.
static_assert(FGB_MAX_STORAGE_BUFFERS <= 0x10000);
constexpr uint64_t kLateCommandsBytes = FGB_MESHLET_COMMANDS_OFFSET + sizeof(gpu::MeshletTaskCommand);
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
  if (settings.debugView == DebugView::Lod || settings.debugView == DebugView::Clusters) {
    // The views' colours live in debug variants only (shaders/CMakeLists.txt).
    desc.meshShader = shaders::variantPath(desc.meshShader, "debug");
    desc.fragmentShader = shaders::variantPath(desc.fragmentShader, "debug");
  }
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
  // Refused on such a device whatever the scene holds, so a path is usable or not per device.
  if (!init.device.meshShaders())
    throw InputError("render.path=" + init.path.source + " needs VK_EXT_mesh_shader (task and mesh shaders), which " +
                     init.device.adapter().name + " lacks");
  if (!enabled()) return;
  lodThreshold_ = lod_ ? init.settings.lodThresholdScenePixels() : 0.0f;
  // The small-triangle test knows the sample positions only where they are the standard ones.
  const uint32_t samples = init.settings.msaa;
  const bool smallTriangles = samples == 1 || init.device.standardSampleLocations();
  meshFlags_ = (smallTriangles ? gpu::kMeshletSmallTriangles : 0u) | samples << gpu::kMeshletSamplesShift;
  injectNan_ = init.settings.injectNanPass == "Meshlet Render";
  injectBias_ = init.settings.injectBiasPass == "Meshlet Render";
  if (projectsReversedZ(init.scene.constants)) meshFlags_ |= gpu::kMeshletReversedZ;
  cull_ = init.device.createComputePipeline({"meshlet instance cull", "renderer/meshlets/meshlet_instance_cull.comp"});
  render_ = init.device.createGraphicsPipeline(meshletPipeline(init.settings));
  // The pyramid is built from the single-sampled depth attachment only.
  occlusion_ = init.settings.occlusion && samples == 1;
  if (occlusion_ && init.settings.occlusionHoldBack) meshFlags_ |= gpu::kMeshletHoldBackOdd;
  if (occlusion_) {
    hizBuild_ = init.device.createComputePipeline(
        {"hiz build (depth)", shaders::variantPath("renderer/visbuffer/hiz_build.comp", "depth")});
    lateArgs_ =
        init.device.createComputePipeline({"meshlet late arguments", "renderer/meshlets/meshlet_late_args.comp"});
    // Kept from frame to frame: phase 1 tests against the previous frame's depths.
    hizKeys_ = hizKeys(init.settings.sceneWidth(), init.settings.sceneHeight());
    hiz_ = init.device.createBuffer({"hiz pyramid", 4 * hizKeys_, rhi::kBufferStorage, rhi::MemoryUsage::DeviceLocal});
  }
  statsReadback_ = createReadbackBuffer(init.device, "meshlet stats readback", kStatsBytes);
}

void MeshletFeature::declareReset(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Meshlet Reset", graph::NodeType::Transfer);
  b.commands = node.write(b.commands, Access::TransferDst);
  b.stats = node.write(b.stats, Access::TransferDst);
  if (b.candidates.valid()) b.candidates = node.write(b.candidates, Access::TransferDst);
  node.setJob([b](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().fillBuffer(ctx.buffer(b.commands), 0, FGB_MESHLET_COMMANDS_OFFSET, 0);  // the draw count
    ctx.cmd().fillBuffer(ctx.buffer(b.stats), 0, kStatsBytes, 0);
    if (b.candidates.valid()) ctx.cmd().fillBuffer(ctx.buffer(b.candidates), 0, 4, 0);  // the candidate count
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
    useFrame(push, *scene, ctx.execution());  // the frustum planes, the instances
    push.commands = ctx.storageBufferIndex(b.commands);
    push.stats = ctx.storageBufferIndex(b.stats);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().dispatch((push.instanceCount + FGB_MESHLET_CULL_GROUP_SIZE - 1) / FGB_MESHLET_CULL_GROUP_SIZE);
  });
  node.recordingFixed();
}

// "Meshlet Render"'s push constants that hold for the whole run: the scene's buffers and the flags.
gpu::MeshletPush MeshletFeature::scenePush() const {
  const GpuScene& scene = *scene_;
  const ClusterGeometry& geometry = scene.clusterGeometry;
  gpu::MeshletPush push{};
  push.shading.materials = device_->storageBufferIndex(scene.materials);
  push.shading.clusterCounts = push.shading.clusterIndices = rhi::kInvalidId;
  push.shading.materialSampler = device_->samplerIndex(scene.materialSampler);
  push.shading.flags =
      (injectNan_ ? gpu::kForwardInjectNan : 0u) | (injectBias_ ? gpu::kForwardInjectBias : 0u);
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
  return push;
}

// Phase 1 (or the only one) draws the instance cull's task draws; phase 2 (late, render.occlusion)
// the one task draw over the candidates phase 1 held back.
void MeshletFeature::declareRender(graph::FrameGraph& graph, Blackboard& board, Buffers& b, bool late) const {
  auto& targets = board.get<FrameTargets>();
  auto node =
      addForwardPass(graph, targets, late ? "Meshlet Render (late)" : "Meshlet Render", true, DepthTest::Attachment);
  const graph::BufferHandle commands = late ? b.lateCommands : b.commands;
  node.read(commands, Access::Indirect);
  node.read(commands, Access::StorageRead, kRenderStages);
  b.stats = node.write(b.stats, Access::StorageReadWrite, kRenderStages);
  if (occlusion_) {
    node.read(b.hiz, Access::StorageRead, kRenderStages);
    if (late)
      node.read(b.candidates, Access::StorageRead, kRenderStages);
    else
      b.candidates = node.write(b.candidates, Access::StorageReadWrite, kRenderStages);
  }
  if (targets.exposure.valid()) node.read(targets.exposure, Access::StorageRead, kRenderStages);
  gpu::MeshletPush push = scenePush();
  push.flags |= occlusion_ ? (late ? gpu::kMeshletLate : gpu::kMeshletOcclusion) : 0u;
  const ClusteredLights clusters = readLightLists(node, board, kRenderStages);
  const uint32_t maxDraws = late ? 1 : scene_->instanceCount;
  node.setJob(
      [push, pipeline = render_, b, commands, clusters, maxDraws, scene = scene_](graph::JobContext& context) mutable {
        auto& ctx = rhi::rhiContext(context);
        useFrame(push.shading, *scene, ctx.execution());
        useLightLists(push.shading, ctx, clusters);
        push.commands = ctx.storageBufferIndex(commands);
        push.stats = ctx.storageBufferIndex(b.stats);
        // As ClusterCullPush::occlusion: storage-buffer indices fit 16 bits (static_assert above).
        if (b.hiz.valid()) push.occlusion = ctx.storageBufferIndex(b.hiz) | ctx.storageBufferIndex(b.candidates) << 16;
        ctx.cmd().bindPipeline(pipeline);
        ctx.cmd().push(push);
        ctx.cmd().drawMeshTasksIndirectCount(ctx.buffer(commands), FGB_MESHLET_COMMANDS_OFFSET, ctx.buffer(commands), 0,
                                             maxDraws, kCommandStride);
      });
  node.recordingFixed();
}

// The HiZ pyramid of the depth attachment as it is now: after phase 1 for phase 2 (whose
// arguments it also writes), after phase 2 for the next frame's phase 1.
void MeshletFeature::declareHizBuild(graph::FrameGraph& graph, FrameTargets& targets, Buffers& b, bool late) const {
  auto node =
      graph.addNode(late ? "HiZ Build (late)" : "HiZ Build", graph::NodeType::Compute, graph::QueueClass::Graphics);
  node.read(targets.depth, Access::Sampled);
  b.hiz = node.write(b.hiz, Access::StorageReadWrite);  // each pass reads the level the one before wrote last
  if (!late) {
    node.read(b.candidates, Access::StorageRead);
    b.lateCommands = node.write(b.lateCommands, Access::StorageWrite);
  }
  const graph::Extent extent = targets.extent;
  const uint32_t passes = hizPasses(extent.width, extent.height);
  const uint32_t sampler = device_->samplerIndex(scene_->linearClampSampler);
  const uint32_t reversedZ = (meshFlags_ & gpu::kMeshletReversedZ) != 0 ? 1u : 0u;
  node.setJob([pipeline = hizBuild_, args = lateArgs_, b, depth = targets.depth, extent, passes, sampler, reversedZ,
               late](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    gpu::HizPush push{ctx.sampledTextureIndex(depth),
                      ctx.storageBufferIndex(b.hiz),
                      extent.width,
                      extent.height,
                      0,
                      sampler,
                      reversedZ};
    cmd.bindPipeline(pipeline);
    for (uint32_t pass = 0; pass < passes; ++pass) {
      if (pass > 0) cmd.computeBarrier();  // a pass reads the level the one before wrote last
      push.sourceLevel = pass * FGB_HIZ_PASS_LEVELS;
      cmd.push(push);
      const HizGroups groups = hizPassGroups(extent.width, extent.height, pass);
      cmd.dispatch(groups.x, groups.y);
    }
    if (late) return;
    // Under validation every dispatch of the node counts as accessing every buffer it declared.
    cmd.computeBarrier();
    cmd.bindPipeline(args);
    cmd.push(gpu::MeshletLateArgsPush{ctx.storageBufferIndex(b.candidates), ctx.storageBufferIndex(b.lateCommands)});
    cmd.dispatch(1);
  });
  node.recordingFixed();
}

void MeshletFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  Buffers b;
  const uint64_t commandBytes = FGB_MESHLET_COMMANDS_OFFSET + uint64_t{kCommandStride} * scene_->instanceCount;
  b.commands = graph.createBuffer("meshlet task draws", {commandBytes, {}});
  b.stats = graph.createBuffer("meshlet stats", {kStatsBytes, {}});
  if (occlusion_) {
    // Written by "HiZ Build (late)", read by the next frame's "Meshlet Render" (task shader).
    const graph::ImportState hizState{graph::kStageComputeShader | graph::kStageTaskShader,
                                      graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
                                      graph::Layout::Undefined, graph::QueueClass::Graphics};
    b.hiz = graph.importBuffer("hiz pyramid", {4 * hizKeys_, {}}, rhi::external(hiz_), hizState, hizState);
    b.candidates = graph.createBuffer("occlusion candidates", {4 * (uint64_t{drawCount_} + 1), {}});
    b.lateCommands = graph.createBuffer("meshlet late task draws", {kLateCommandsBytes, {}});
  }
  declareReset(graph, b);
  declareInstanceCull(graph, b);
  declareRender(graph, board, b, false);
  if (occlusion_) {
    auto& targets = board.get<FrameTargets>();
    declareHizBuild(graph, targets, b, false);
    declareRender(graph, board, b, true);
    declareHizBuild(graph, targets, b, true);  // kept for the next frame's phase 1
  }
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
  if (occlusion_) {
    stats["meshlet_occlusion_phase1_occluded"] = read.occluded;
    stats["meshlet_occlusion_phase2_recovered"] = read.recovered;
    stats["meshlet_occlusion_culled"] = double(read.occluded) - read.recovered;
  }
}

}  // namespace fgb::features
