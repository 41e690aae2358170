#include "visbuffer_feature.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <fgb/rhi/job_context.hpp>
#include <fgb/scene/frustum.hpp>
#include <fgb/shaders/registry.hpp>

#include "../context/handles.hpp"

namespace fgb::features {
namespace {

using graph::Access;
constexpr graph::QueueClass kQueue = graph::QueueClass::Graphics;

// Mirrors VisCounters in shaders/renderer/include/visbuffer.glsl.
struct VisCounters {
  uint32_t visibleClusters;
  uint32_t filterGroups[3];
  uint32_t smallTriangles;
  uint32_t smallGroups[3];
  uint64_t largeTotals;  // high 24 bits: large triangles, low 40 bits: their tile jobs
  uint32_t largeTriangles;
  uint32_t tileJobs;
  uint32_t tileGroups[3];
  uint32_t overflow;
};
static_assert(sizeof(VisCounters) == 64);
constexpr uint64_t kFilterArgsOffset = offsetof(VisCounters, filterGroups);
constexpr uint64_t kSmallArgsOffset = offsetof(VisCounters, smallGroups);
constexpr uint64_t kTileArgsOffset = offsetof(VisCounters, tileGroups);

// Mirrors the push block of shaders/renderer/visbuffer/cluster_cull.comp.
struct CullPush {
  glm::vec4 planes[6];
  uint32_t frame;
  uint32_t instances;
  uint32_t draws;
  uint32_t clusters;
  uint32_t counters;
  uint32_t visible;
  uint32_t drawCount;
};
static_assert(sizeof(CullPush) <= rhi::kPushConstantBytes);

// Mirrors shaders/renderer/visbuffer/vis_args.comp.
struct ArgsPush {
  uint32_t counters;
  uint32_t args;
  uint32_t smallPerGroup;
  uint32_t tileJobCapacity;
};

// Mirrors the push block of shaders/renderer/include/visbuffer_triangle.glsl.
struct VisPush {
  uint32_t frame, instances, materials, draws, clusters, indices, vertices;
  uint32_t positions;               // cluster vertices (ClusterGeometry::vertices)
  uint32_t normals, tangents, uvs;  // float offsets of the vertex streams
  uint32_t counters, args, visible, smallList, largeList, largeCapacity, words, depthOut, hdr;
  uint32_t materialSampler, lights, clusterCounts, clusterIndices, flags;
  uint32_t tileJobs, tileJobCapacity, pad;
  glm::vec4 background;
};
static_assert(offsetof(VisPush, background) == 112 && sizeof(VisPush) == rhi::kPushConstantBytes);

constexpr uint32_t kFlagReversedZ = 1;
constexpr uint32_t kFlagLargeTiles = 2;
constexpr uint32_t kFlagSerialSubgroups = 4;  // CPU device: see triangle_filter.comp
constexpr uint32_t kRasterGroupSize = 64;     // visibility_raster.comp's local size
constexpr uint64_t kLargeTriangleBytes = 64;  // 4 uvec4 (packLargeTriangle in visbuffer_triangle.glsl)
constexpr uint64_t kTileJobBytes = 8;         // uvec2: large-list slot, job index within the triangle
constexpr uint32_t kShadeGroupSize = 8;       // material_shade.comp: 8 x 8
constexpr uint32_t kClearGroupSize = 8;       // vis_clear.comp: 8 x 8

// Mirrors the push block of shaders/renderer/visbuffer/vis_clear.comp.
struct ClearPush {
  uint32_t words;
  uint32_t width;
  uint32_t height;
};

// Reversed Z: the projection maps nearer points to larger depth.
bool projectsReversedZ(const FrameConstantsGpu& constants) {
  const float near = constants.depthRange.x;
  const auto depthAt = [&](float distance) {
    const glm::vec4 clip = constants.proj * glm::vec4(0.0f, 0.0f, -distance, 1.0f);
    return clip.z / clip.w;
  };
  return depthAt(2.0f * near) > depthAt(4.0f * near);
}

}  // namespace

struct VisBufferFeature::Buffers {
  graph::BufferHandle counters;    // VisCounters, added to by the culling nodes
  graph::BufferHandle cullArgs;    // snapshot after "Cluster Cull": "Triangle Filter"'s arguments
  graph::BufferHandle rasterArgs;  // snapshot after "Triangle Filter": "Visibility Raster"'s arguments
  graph::BufferHandle visible;
  graph::BufferHandle smallList;
  graph::BufferHandle largeList;
  graph::BufferHandle tileJobs;
  graph::BufferHandle words;       // the buffer backing, or
  graph::TextureHandle wordImage;  // the image backing (render.vis_backing)
  graph::BufferHandle depth;
  graph::Extent extent;
  VisPush push{};  // the scene's persistent indices; per-node handles are filled in by the jobs
};

void VisBufferFeature::initialize(FeatureInit& init) {
  device_ = &init.device;
  scene_ = &init.scene;
  drawCount_ = init.settings.renderPath == RenderPath::VisBuffer ? init.scene.clusterGeometry.drawCount : 0;
  if (!enabled()) return;
  if (!init.device.shaderCapabilities().bufferInt64Atomics)
    throw DeviceError("render.path=visbuffer needs 64-bit storage-buffer atomics (shaderBufferInt64Atomics), which " +
                      init.device.adapter().name + " lacks");
  // Large triangles are few (most of a dense scene covers a pixel or less); a list overflow is
  // counted and reported as the "vis_large_overflow" statistic.
  const uint64_t pixels = uint64_t{init.settings.sceneWidth()} * init.settings.sceneHeight();
  largeCapacity_ = uint32_t(std::min<uint64_t>(std::max<uint64_t>(init.scene.clusterGeometry.triangles, 1),
                                               std::max<uint64_t>(65536, pixels / 8)));
  // A large triangle has one tile job per 16 8x8 tiles of its box, rounded up: room for one job
  // per triangle plus pixels / 16 more (boxes adding up to 64 screens' worth of tiles).
  tileJobCapacity_ = uint32_t(std::min<uint64_t>(uint64_t{largeCapacity_} + pixels / 16, UINT32_MAX));
  reversedZ_ = projectsReversedZ(init.scene.constants);
  if (init.settings.visBacking == VisBacking::Auto)
    throw std::logic_error("render.vis_backing=auto reached the visibility buffer unresolved (resolveDeviceSettings)");
  imageBacking_ = init.settings.visBacking == VisBacking::Image;
  // The word accesses are compiled per backing: the image variants declare 64-bit image
  // capabilities, which a device without them refuses even where unused.
  const auto backed = [&](const char* shader) {
    return imageBacking_ ? shaders::variantPath(shader, "image") : std::string(shader);
  };
  pipelines_.cull = init.device.createComputePipeline({"cluster cull", "renderer/visbuffer/cluster_cull.comp"});
  pipelines_.args = init.device.createComputePipeline({"visibility arguments", "renderer/visbuffer/vis_args.comp"});
  pipelines_.filter = init.device.createComputePipeline({"triangle filter", "renderer/visbuffer/triangle_filter.comp"});
  pipelines_.raster =
      init.device.createComputePipeline({"visibility raster", backed("renderer/visbuffer/visibility_raster.comp")});
  pipelines_.shade =
      init.device.createComputePipeline({"material shade", backed("renderer/visbuffer/material_shade.comp")});
  if (imageBacking_)
    pipelines_.clearImage =
        init.device.createComputePipeline({"visibility clear", "renderer/visbuffer/vis_clear.comp"});
  statsReadback_ = init.device.createBuffer(
      {"visibility stats readback", sizeof(VisCounters), rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  std::memset(init.device.mapped(statsReadback_).data(), 0, sizeof(VisCounters));
}

VisBufferFeature::Buffers VisBufferFeature::declareBuffers(graph::FrameGraph& graph,
                                                           const FrameTargets& targets) const {
  const GpuScene& scene = *scene_;
  const ClusterGeometry& geometry = scene.clusterGeometry;
  Buffers b;
  b.extent = targets.extent;
  const uint64_t pixels = uint64_t{targets.extent.width} * targets.extent.height;
  b.counters = graph.createBuffer("vis counters", {sizeof(VisCounters), {}});
  b.cullArgs = graph.createBuffer("cluster cull args", {sizeof(VisCounters), {}});
  b.rasterArgs = graph.createBuffer("triangle filter args", {sizeof(VisCounters), {}});
  b.visible = graph.createBuffer("visible clusters", {uint64_t{4} * geometry.drawCount, {}});
  b.smallList = graph.createBuffer("small triangles", {uint64_t{32} * geometry.triangles, {}});  // 2 uvec4 each
  b.largeList = graph.createBuffer("large triangles", {kLargeTriangleBytes * largeCapacity_, {}});
  b.tileJobs = graph.createBuffer("large triangle tile jobs", {kTileJobBytes * tileJobCapacity_, {}});
  if (imageBacking_)
    b.wordImage = graph.createTexture("visibility buffer", {graph::Format::R64Uint, targets.extent});
  else
    b.words = graph.createBuffer("visibility buffer", {uint64_t{8} * pixels, {}});
  b.depth = graph.createBuffer("visibility depth", {uint64_t{4} * pixels, {}});

  VisPush& p = b.push;
  p.frame = device_->storageBufferIndex(scene.frameConstants);
  p.instances = device_->storageBufferIndex(scene.instances);
  p.materials = device_->storageBufferIndex(scene.materials);
  p.draws = device_->storageBufferIndex(geometry.draws);
  p.clusters = device_->storageBufferIndex(geometry.clusters);
  p.indices = device_->storageBufferIndex(geometry.packedTriangles);
  p.vertices = device_->storageBufferIndex(scene.vertices);
  p.positions = device_->storageBufferIndex(geometry.vertices);
  p.normals = uint32_t(scene.streams.normals / 4);
  p.tangents = uint32_t(scene.streams.tangents / 4);
  p.uvs = uint32_t(scene.streams.uvs / 4);
  p.largeCapacity = largeCapacity_;
  p.tileJobCapacity = tileJobCapacity_;
  p.materialSampler = device_->samplerIndex(scene.materialSampler);
  p.lights = device_->storageBufferIndex(scene.lights);
  p.clusterCounts = p.clusterIndices = rhi::kInvalidId;
  p.flags = (reversedZ_ ? kFlagReversedZ : 0u) | (device_->adapter().type == "cpu" ? kFlagSerialSubgroups : 0u);
  p.background = {targets.background[0], targets.background[1], targets.background[2], targets.background[3]};
  return b;
}

void VisBufferFeature::declareClear(graph::FrameGraph& graph, Buffers& b) const {
  // The image backing is zeroed by a dispatch (vis_clear.comp), so the node is compute there.
  auto node =
      graph.addNode("Visibility Clear", imageBacking_ ? graph::NodeType::Compute : graph::NodeType::Transfer, kQueue);
  if (imageBacking_)
    b.wordImage = node.write(b.wordImage, Access::StorageWrite);
  else
    b.words = node.write(b.words, Access::TransferDst);
  b.counters = node.write(b.counters, Access::TransferDst);
  // The argument snapshots are zeroed too: the culling nodes then update them (read-write).
  b.cullArgs = node.write(b.cullArgs, Access::TransferDst);
  b.rasterArgs = node.write(b.rasterArgs, Access::TransferDst);
  const uint64_t wordBytes = uint64_t{8} * b.extent.width * b.extent.height;
  node.setJob([b, wordBytes, clearImage = pipelines_.clearImage](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    if (b.wordImage.valid()) {
      ctx.cmd().bindPipeline(clearImage);
      ctx.cmd().push(ClearPush{ctx.storageTextureIndex(b.wordImage), b.extent.width, b.extent.height});
      ctx.cmd().dispatch((b.extent.width + kClearGroupSize - 1) / kClearGroupSize,
                         (b.extent.height + kClearGroupSize - 1) / kClearGroupSize);
    } else {
      ctx.cmd().fillBuffer(ctx.buffer(b.words), 0, wordBytes, 0);  // 0: no triangle (see visbuffer.glsl)
    }
    for (const auto counters : {b.counters, b.cullArgs, b.rasterArgs})
      ctx.cmd().fillBuffer(ctx.buffer(counters), 0, sizeof(VisCounters), 0);
  });
}

void VisBufferFeature::declareClusterCull(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Cluster Cull", graph::NodeType::Compute, kQueue);
  b.counters = node.write(b.counters, Access::StorageReadWrite);
  b.visible = node.write(b.visible, Access::StorageWrite);
  // Read-write, not write: under validation the node's read-only binding exposes every buffer it
  // declared, and the cull shader reads that binding, so sync validation counts it as a reader.
  b.cullArgs = node.write(b.cullArgs, Access::StorageReadWrite);
  CullPush push{};
  const auto frustum = scene::Frustum::fromMatrix(scene_->constants.viewProj);
  for (size_t i = 0; i < 6; ++i) push.planes[i] = frustum.planes[i];
  push.frame = b.push.frame;
  push.instances = b.push.instances;
  push.draws = b.push.draws;
  push.clusters = b.push.clusters;
  push.drawCount = drawCount_;
  node.setJob([push, pipelines = pipelines_, counters = b.counters, visible = b.visible, args = b.cullArgs,
               jobCapacity = tileJobCapacity_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    push.counters = ctx.storageBufferIndex(counters);
    push.visible = ctx.storageBufferIndex(visible);
    cmd.bindPipeline(pipelines.cull);
    cmd.push(push);
    cmd.dispatch((push.drawCount + 63) / 64);
    cmd.computeBarrier();  // the arguments read every workgroup's count
    cmd.bindPipeline(pipelines.args);
    cmd.push(ArgsPush{push.counters, ctx.storageBufferIndex(args), kRasterGroupSize, jobCapacity});
    cmd.dispatch(1);
  });
}

void VisBufferFeature::declareTriangleFilter(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Triangle Filter", graph::NodeType::Compute, kQueue);
  node.read(b.cullArgs, Access::Indirect);
  node.read(b.cullArgs, Access::StorageRead);
  node.read(b.visible, Access::StorageRead);
  b.counters = node.write(b.counters, Access::StorageReadWrite);
  b.smallList = node.write(b.smallList, Access::StorageWrite);
  b.largeList = node.write(b.largeList, Access::StorageWrite);
  b.tileJobs = node.write(b.tileJobs, Access::StorageWrite);
  b.rasterArgs = node.write(b.rasterArgs, Access::StorageReadWrite);  // see cullArgs in Cluster Cull
  node.setJob([push = b.push, pipelines = pipelines_, b](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    push.counters = ctx.storageBufferIndex(b.counters);
    push.args = ctx.storageBufferIndex(b.cullArgs);
    push.visible = ctx.storageBufferIndex(b.visible);
    push.smallList = ctx.storageBufferIndex(b.smallList);
    push.largeList = ctx.storageBufferIndex(b.largeList);
    push.tileJobs = ctx.storageBufferIndex(b.tileJobs);
    cmd.bindPipeline(pipelines.filter);
    cmd.push(push);
    cmd.dispatchIndirect(ctx.buffer(b.cullArgs), kFilterArgsOffset);
    cmd.computeBarrier();
    cmd.bindPipeline(pipelines.args);
    cmd.push(ArgsPush{push.counters, ctx.storageBufferIndex(b.rasterArgs), kRasterGroupSize, push.tileJobCapacity});
    cmd.dispatch(1);
  });
}

void VisBufferFeature::declareRaster(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Visibility Raster", graph::NodeType::Compute, kQueue);
  node.read(b.rasterArgs, Access::Indirect);
  node.read(b.rasterArgs, Access::StorageRead);
  node.read(b.visible, Access::StorageRead);
  node.read(b.smallList, Access::StorageRead);
  node.read(b.largeList, Access::StorageRead);
  node.read(b.tileJobs, Access::StorageRead);
  if (b.wordImage.valid())
    b.wordImage = node.write(b.wordImage, Access::StorageReadWrite);
  else
    b.words = node.write(b.words, Access::StorageReadWrite);
  node.setJob([push = b.push, pipelines = pipelines_, b](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    push.args = ctx.storageBufferIndex(b.rasterArgs);
    push.visible = ctx.storageBufferIndex(b.visible);
    push.smallList = ctx.storageBufferIndex(b.smallList);
    push.largeList = ctx.storageBufferIndex(b.largeList);
    push.tileJobs = ctx.storageBufferIndex(b.tileJobs);
    push.words = b.wordImage.valid() ? ctx.storageTextureIndex(b.wordImage) : ctx.storageBufferIndex(b.words);
    cmd.bindPipeline(pipelines.raster);
    cmd.push(push);
    cmd.dispatchIndirect(ctx.buffer(b.rasterArgs), kSmallArgsOffset);
    // No barrier between the two: atomic max commutes. (A copy: the job runs every frame.)
    VisPush tiles = push;
    tiles.flags |= kFlagLargeTiles;
    cmd.push(tiles);
    cmd.dispatchIndirect(ctx.buffer(b.rasterArgs), kTileArgsOffset);
  });
}

// Material Shade also copies the culling counters to the host (statistics). A node of its own
// reading them after "Triangle Filter" ran between "Visibility Raster" and "Material Shade", on
// the critical path (H100: 5 us plus a ~20 us bubble); here the 64-byte copy is recorded before the
// dispatch with no barrier between them, so it runs beside the shading, and its source's barrier
// (filter's compute write -> transfer read) joins the one shading waits at anyway.
void VisBufferFeature::declareShade(graph::FrameGraph& graph, Blackboard& board, Buffers& b) const {
  auto& targets = board.get<FrameTargets>();
  const graph::ImportState hostState{graph::kStageHost | graph::kStageTransfer,
                                     graph::kAccessHostRead | graph::kAccessTransferWrite, graph::Layout::Undefined,
                                     graph::QueueClass::Graphics};
  auto stats = graph.importBuffer("visibility stats readback", {sizeof(VisCounters), {}}, rhi::external(statsReadback_),
                                  hostState, hostState);
  auto node = graph.addNode("Material Shade", graph::NodeType::Compute, kQueue);
  if (b.wordImage.valid())
    node.read(b.wordImage, Access::StorageRead);
  else
    node.read(b.words, Access::StorageRead);
  node.read(b.visible, Access::StorageRead);
  node.read(b.rasterArgs, Access::TransferSrc);
  stats = node.write(stats, Access::TransferDst);
  b.depth = node.write(b.depth, Access::StorageWrite);
  targets.hdr = node.write(targets.hdr, Access::StorageWrite);
  ClusteredLights clusters;
  if (const auto* published = board.find<ClusteredLights>()) {
    clusters = *published;
    node.read(clusters.counts, Access::StorageRead);
    node.read(clusters.indices, Access::StorageRead);
  }
  // Shading pre-exposes what it writes, like every colour pass (auto exposure: this frame's state).
  if (targets.exposure.valid()) node.read(targets.exposure, Access::StorageRead);
  node.setJob([push = b.push, pipelines = pipelines_, b, hdr = targets.hdr, clusters,
               stats](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    cmd.copyBuffer(ctx.buffer(b.rasterArgs), ctx.buffer(stats), sizeof(VisCounters));
    push.words = b.wordImage.valid() ? ctx.storageTextureIndex(b.wordImage) : ctx.storageBufferIndex(b.words);
    push.visible = ctx.storageBufferIndex(b.visible);
    push.depthOut = ctx.storageBufferIndex(b.depth);
    push.hdr = ctx.storageTextureIndex(hdr);
    if (clusters.counts.valid()) {
      push.clusterCounts = ctx.storageBufferIndex(clusters.counts);
      push.clusterIndices = ctx.storageBufferIndex(clusters.indices);
    }
    cmd.bindPipeline(pipelines.shade);
    cmd.push(push);
    cmd.dispatch((b.extent.width + kShadeGroupSize - 1) / kShadeGroupSize,
                 (b.extent.height + kShadeGroupSize - 1) / kShadeGroupSize);
  });
  targets.color = targets.hdr;  // single-sampled: later forward passes load the shaded image
  targets.colorCleared = true;
  // No depth attachment is written: the later colour passes test against this buffer in their
  // fragment shaders (DepthTest::OpaqueDepthBuffer), with no copy into a depth image.
  targets.opaqueDepth = b.depth;
}

void VisBufferFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  auto& targets = board.get<FrameTargets>();
  if (targets.samples != 1) throw std::logic_error("visibility buffer with MSAA (render settings should refuse it)");
  Buffers b = declareBuffers(graph, targets);
  declareClear(graph, b);
  declareClusterCull(graph, b);
  declareTriangleFilter(graph, b);
  declareRaster(graph, b);
  declareShade(graph, board, b);
  board.set(VisibilityOutputs{b.rasterArgs, b.visible, b.words, b.wordImage});
}

void VisBufferFeature::addStats(std::map<std::string, double>& stats) const {
  if (!enabled()) return;
  VisCounters read{};
  std::memcpy(&read, device_->mapped(statsReadback_).data(), sizeof(read));
  stats["vis_backing_image"] = imageBacking_ ? 1.0 : 0.0;  // render.vis_backing as run: 1 image, 0 buffer
  stats["vis_clusters"] = drawCount_;
  stats["vis_clusters_visible"] = read.visibleClusters;
  stats["vis_triangles_small"] = read.smallTriangles;
  stats["vis_triangles_large"] = read.largeTriangles;
  stats["vis_triangles_rasterised"] = double(read.smallTriangles) + read.largeTriangles;
  stats["vis_raster_tile_jobs"] = read.tileJobs;
  stats["vis_large_overflow"] = read.overflow;
}

}  // namespace fgb::features
