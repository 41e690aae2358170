#include "visbuffer_feature.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <fgb/rhi/job_context.hpp>
#include <fgb/shaders/registry.hpp>
#include <string>

#include "../context/handles.hpp"
#include "hiz_pyramid.hpp"
#include "renderer/shared/visbuffer.h"

namespace fgb::features {
namespace {

using graph::Access;
constexpr graph::QueueClass kQueue = graph::QueueClass::Graphics;

using gpu::VisCounters;
constexpr uint64_t kFilterArgsOffset = offsetof(VisCounters, filterGroups);
constexpr uint64_t kSmallArgsOffset = offsetof(VisCounters, smallGroups);
constexpr uint64_t kTileArgsOffset = offsetof(VisCounters, tileGroups);
// ClusterCullPush::occlusion and Material Shade's VisPush::args pack two storage-buffer indices in
// 16 bits each (the latter with kVisNoPhase for none).
static_assert(FGB_MAX_STORAGE_BUFFERS <= gpu::kVisNoPhase);
// Material Shade's first workgroup copies both phases' counters, a word per invocation.
static_assert(sizeof(VisCounters) == uint64_t{4} * gpu::kVisCounterWords &&
              2 * gpu::kVisCounterWords <= FGB_VIS_SHADE_GROUP_SIZE * FGB_VIS_SHADE_GROUP_SIZE);

// Material Shade's shader: the backing's word accesses, and the debug views' colours only where a
// debug view needs them (shaders/CMakeLists.txt's "debug" variants).
std::string materialShadeShader(const RenderSettings& settings) {
  const bool image = settings.visBacking == VisBacking::Image;
  const bool debug = settings.debugView == DebugView::Lod || settings.debugView == DebugView::Clusters;
  const char* shader = "renderer/visbuffer/material_shade.comp";
  if (image && debug) return shaders::variantPath(shader, "image_debug");
  if (image) return shaders::variantPath(shader, "image");
  if (debug) return shaders::variantPath(shader, "debug");
  return shader;
}

}  // namespace

gpu::VisPush visScenePush(rhi::Device& device, const GpuScene& scene) {
  const ClusterGeometry& geometry = scene.clusterGeometry;
  gpu::VisPush p{};
  p.materials = device.storageBufferIndex(scene.materials);
  p.clusters = device.storageBufferIndex(geometry.clusters);
  p.indices = device.storageBufferIndex(geometry.packedTriangles);
  p.vertices = device.storageBufferIndex(scene.vertices);
  p.positions = device.storageBufferIndex(geometry.vertices);
  p.normals = uint32_t(scene.streams.normals / 4);
  p.tangents = uint32_t(scene.streams.tangents / 4);
  p.uvs = uint32_t(scene.streams.uvs / 4);
  p.materialSampler = device.samplerIndex(scene.materialSampler);
  p.clusterCounts = p.clusterIndices = rhi::kInvalidId;
  p.flags = (projectsReversedZ(scene.constants) ? gpu::kFlagReversedZ : 0u) |
            (device.adapter().type == "cpu" ? gpu::kFlagSerialSubgroups : 0u);
  return p;
}

// One culling phase's counters: render.occlusion runs the filter and raster twice, the second
// time ("late") with counters of its own (the lists are reused: phase 1's raster has read them).
struct VisPhase {
  std::string_view suffix;         // "" or " (late)", appended to the node names
  graph::BufferHandle counters;    // VisCounters, added to by the phase's culling nodes
  graph::BufferHandle cullArgs;    // snapshot after the cull: the filter's arguments
  graph::BufferHandle rasterArgs;  // snapshot after the filter: the raster's arguments
};

struct VisBufferFeature::Buffers {
  VisPhase early{"", {}, {}, {}};
  VisPhase late{" (late)", {}, {}, {}};  // render.occlusion only
  graph::BufferHandle visible;
  graph::BufferHandle smallList;
  graph::BufferHandle largeList;
  graph::BufferHandle tileJobs;
  graph::BufferHandle words;       // the buffer backing, or
  graph::TextureHandle wordImage;  // the image backing (render.vis_backing)
  graph::BufferHandle depth;
  graph::BufferHandle hiz;          // render.occlusion: the HiZ pyramid (persistent), and
  graph::BufferHandle candidates;   // the clusters phase 1 held back
  graph::Extent extent;
  gpu::VisPush push{};  // the scene's persistent indices; per-node handles are filled in by the jobs

  // The visibility words in a node's declarations and in its job, whichever backing holds them.
  void readWords(graph::NodeBuilder& node) const {
    if (wordImage.valid())
      node.read(wordImage, Access::StorageRead);
    else
      node.read(words, Access::StorageRead);
  }
  void writeWords(graph::NodeBuilder& node, Access access) {
    if (wordImage.valid())
      wordImage = node.write(wordImage, access);
    else
      words = node.write(words, access);
  }
  [[nodiscard]] uint32_t wordsIndex(const rhi::JobContext& ctx) const {
    return wordImage.valid() ? ctx.storageTextureIndex(wordImage) : ctx.storageBufferIndex(words);
  }
};

void VisBufferFeature::initialize(FeatureInit& init) {
  device_ = &init.device;
  scene_ = &init.scene;
  drawCount_ = init.scene.clusterGeometry.drawCount;  // the path uploads the clusters (upload.clusters)
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
  injectBias_ = init.settings.injectBiasPass == "Material Shade";
  if (init.settings.visBacking == VisBacking::Auto)
    throw std::logic_error("render.vis_backing=auto reached the visibility buffer unresolved (resolveDeviceSettings)");
  imageBacking_ = init.settings.visBacking == VisBacking::Image;
  occlusion_ = init.settings.occlusion;
  occlusionHoldBack_ = occlusion_ && init.settings.occlusionHoldBack;
  lodThreshold_ = lod_ ? init.settings.lodThresholdScenePixels() : 0.0f;
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
  pipelines_.shade = init.device.createComputePipeline({"material shade", materialShadeShader(init.settings)});
  if (imageBacking_)
    pipelines_.clearImage =
        init.device.createComputePipeline({"visibility clear", "renderer/visbuffer/vis_clear.comp"});
  if (occlusion_) {
    pipelines_.cullLate =
        init.device.createComputePipeline({"cluster cull late", "renderer/visbuffer/cluster_cull_late.comp"});
    pipelines_.hizBuild = init.device.createComputePipeline({"hiz build", backed("renderer/visbuffer/hiz_build.comp")});
    // Kept from frame to frame: phase 1 tests against the previous frame's depths.
    hizKeys_ = hizKeys(init.settings.sceneWidth(), init.settings.sceneHeight());
    hiz_ = init.device.createBuffer({"hiz pyramid", 4 * hizKeys_, rhi::kBufferStorage, rhi::MemoryUsage::DeviceLocal});
  }
  // Kept from frame to frame, empty between frames: "Material Shade" empties the words it read.
  wordsExtent_ = {init.settings.sceneWidth(), init.settings.sceneHeight(), 1};
  if (imageBacking_)
    wordImage_ = init.device.createTexture(
        {"visibility buffer", graph::Format::R64Uint, wordsExtent_, 1, 1, 1, rhi::kTextureStorage});
  else
    words_ = init.device.createBuffer({"visibility buffer", uint64_t{8} * pixels,
                                       rhi::kBufferStorage | rhi::kBufferTransferDst | rhi::kBufferTransferSrc,
                                       rhi::MemoryUsage::DeviceLocal});
  clearWordsOnce(init.device);
  statsReadback_ = init.device.createBuffer(
      {"visibility stats readback", 2 * sizeof(VisCounters), rhi::kBufferStorage, rhi::MemoryUsage::Readback});
  std::memset(init.device.mapped(statsReadback_).data(), 0, 2 * sizeof(VisCounters));
}

VisBufferFeature::Buffers VisBufferFeature::declareBuffers(graph::FrameGraph& graph,
                                                           const FrameTargets& targets) const {
  const GpuScene& scene = *scene_;
  const ClusterGeometry& geometry = scene.clusterGeometry;
  Buffers b;
  b.extent = targets.extent;
  const uint64_t pixels = uint64_t{targets.extent.width} * targets.extent.height;
  b.early.counters = graph.createBuffer("vis counters", {sizeof(VisCounters), {}});
  b.early.cullArgs = graph.createBuffer("cluster cull args", {sizeof(VisCounters), {}});
  b.early.rasterArgs = graph.createBuffer("triangle filter args", {sizeof(VisCounters), {}});
  if (occlusion_) {
    b.late.counters = graph.createBuffer("vis counters (late)", {sizeof(VisCounters), {}});
    b.late.cullArgs = graph.createBuffer("cluster cull args (late)", {sizeof(VisCounters), {}});
    b.late.rasterArgs = graph.createBuffer("triangle filter args (late)", {sizeof(VisCounters), {}});
    b.candidates = graph.createBuffer("occlusion candidates", {uint64_t{4} * geometry.drawCount, {}});
    // Written by "HiZ Build" from phase 1's depths, read by "Cluster Cull (late)" and by the next
    // frame's "Cluster Cull": all compute on the graphics queue.
    const graph::ImportState hizState{graph::kStageComputeShader,
                                      graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
                                      graph::Layout::Undefined, graph::QueueClass::Graphics};
    b.hiz = graph.importBuffer("hiz pyramid", {4 * hizKeys_, {}}, rhi::external(hiz_), hizState, hizState);
  }
  b.visible = graph.createBuffer("visible clusters", {uint64_t{4} * geometry.drawCount, {}});
  b.smallList = graph.createBuffer("small triangles", {uint64_t{32} * geometry.triangles, {}});  // 2 uvec4 each
  b.largeList = graph.createBuffer("large triangles", {uint64_t{gpu::kLargeTriangleBytes} * largeCapacity_, {}});
  b.tileJobs = graph.createBuffer("large triangle tile jobs", {uint64_t{gpu::kTileJobBytes} * tileJobCapacity_, {}});
  if (targets.extent.width != wordsExtent_.width || targets.extent.height != wordsExtent_.height)
    throw std::logic_error("the visibility buffer was sized for other scene passes");
  if (imageBacking_)
    b.wordImage = graph.importTexture("visibility buffer", {graph::Format::R64Uint, targets.extent},
                                      rhi::external(wordImage_), wordsState(), wordsState());
  else
    b.words = graph.importBuffer("visibility buffer", {uint64_t{8} * pixels, {}}, rhi::external(words_), wordsState(),
                                 wordsState());
  b.depth = graph.createBuffer("visibility depth", {uint64_t{4} * pixels, {}});

  gpu::VisPush& p = b.push;
  p = visScenePush(*device_, scene);
  p.draws = device_->storageBufferIndex(geometry.draws);
  p.largeCapacity = largeCapacity_;
  p.tileJobCapacity = tileJobCapacity_;
  p.background = {targets.background[0], targets.background[1], targets.background[2], targets.background[3]};
  return b;
}

// Zeroes the culling counters and their snapshots every frame: the culling nodes then add to them
// (read-write). The visibility words are not cleared here: they start empty (clearWordsOnce) and
// "Material Shade" empties each word it reads, so a frame never pays for a full-screen clear.
void VisBufferFeature::declareClear(graph::FrameGraph& graph, Buffers& b) {
  auto node = graph.addNode("Visibility Clear", graph::NodeType::Transfer, kQueue);
  std::vector<graph::BufferHandle> zeroed;
  for (VisPhase* phase : {&b.early, &b.late}) {
    if (!phase->counters.valid()) continue;
    for (graph::BufferHandle* counters : {&phase->counters, &phase->cullArgs, &phase->rasterArgs}) {
      *counters = node.write(*counters, Access::TransferDst);
      zeroed.push_back(*counters);
    }
  }
  node.setJob([zeroed](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    for (const auto counters : zeroed) ctx.cmd().fillBuffer(ctx.buffer(counters), 0, sizeof(VisCounters), 0);
  });
  node.recordingFixed();
}

// The persistent words' state between frames: compute on the graphics queue touches them last
// ("Material Shade" empties them) and first (the rasters' atomics).
graph::ImportState VisBufferFeature::wordsState() const {
  return {graph::kStageComputeShader, graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
          imageBacking_ ? graph::Layout::General : graph::Layout::Undefined, kQueue};
}

// Zeroes the new words once (0: no triangle, see visbuffer.glsl), in a graph of its own run now, so
// the frame graph's first frame finds them in the state every later frame does (wordsState).
void VisBufferFeature::clearWordsOnce(rhi::Device& device) const {
  const graph::Extent& extent = wordsExtent_;
  const graph::ImportState fresh{graph::kStageNone, graph::kAccessNone, graph::Layout::Undefined, kQueue};
  graph::FrameGraph graph;
  auto node = graph.addNode("Visibility Buffer First Clear",
                            imageBacking_ ? graph::NodeType::Compute : graph::NodeType::Transfer, kQueue);
  node.sideEffect();
  graph::TextureHandle image;
  graph::BufferHandle buffer;
  const uint64_t bytes = uint64_t{8} * extent.width * extent.height;
  if (imageBacking_)
    image = node.write(graph.importTexture("visibility buffer", {graph::Format::R64Uint, extent},
                                           rhi::external(wordImage_), fresh, wordsState()),
                       Access::StorageWrite);
  else
    buffer =
        node.write(graph.importBuffer("visibility buffer", {bytes, {}}, rhi::external(words_), fresh, wordsState()),
                   Access::TransferDst);
  node.setJob([image, buffer, bytes, extent, clearImage = pipelines_.clearImage](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    if (image.valid()) {
      ctx.cmd().bindPipeline(clearImage);
      ctx.cmd().push(gpu::ClearPush{ctx.storageTextureIndex(image), extent.width, extent.height});
      ctx.cmd().dispatch((extent.width + FGB_VIS_CLEAR_GROUP_SIZE - 1) / FGB_VIS_CLEAR_GROUP_SIZE,
                         (extent.height + FGB_VIS_CLEAR_GROUP_SIZE - 1) / FGB_VIS_CLEAR_GROUP_SIZE);
    } else {
      ctx.cmd().fillBuffer(ctx.buffer(buffer), 0, bytes, 0);
    }
  });
  rhi::GraphOptions options;
  options.name = "visibility buffer first clear";
  options.timestamps = false;
  auto executable = device.compile(std::move(graph), options);
  device.wait(device.execute(*executable));
}

void VisBufferFeature::declareClusterCull(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Cluster Cull", graph::NodeType::Compute, kQueue);
  b.early.counters = node.write(b.early.counters, Access::StorageReadWrite);
  b.visible = node.write(b.visible, Access::StorageWrite);
  // Read-write, not write: under validation the node's read-only binding exposes every buffer it
  // declared, and the cull shader reads that binding, so sync validation counts it as a reader.
  b.early.cullArgs = node.write(b.early.cullArgs, Access::StorageReadWrite);
  if (occlusion_) {
    node.read(b.hiz, Access::StorageRead);
    b.candidates = node.write(b.candidates, Access::StorageWrite);
  }
  gpu::ClusterCullPush push{};
  push.draws = b.push.draws;
  push.clusters = b.push.clusters;
  push.lodThreshold = lodThreshold_;
  // A pixel's id is (cluster draw << 7) | triangle (visbuffer.glsl): 25 bits of draw index.
  if (drawCount_ > gpu::kCullDrawCountMask || drawCount_ > (1u << 25))
    throw std::logic_error("visbuffer: more cluster draws than Cluster Cull can count or pixel ids can name");
  push.drawCount =
      drawCount_ | (reversedZ_ ? gpu::kCullReversedZ : 0u) | (occlusionHoldBack_ ? gpu::kCullHoldBackOdd : 0u);
  node.setJob([push, pipelines = pipelines_, counters = b.early.counters, visible = b.visible, args = b.early.cullArgs,
               hiz = b.hiz, candidates = b.candidates,
               jobCapacity = tileJobCapacity_, scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());
    push.counters = ctx.storageBufferIndex(counters);
    push.visible = ctx.storageBufferIndex(visible);
    if (hiz.valid()) {
      push.occlusion = ctx.storageBufferIndex(hiz) | ctx.storageBufferIndex(candidates) << 16;
      // Whether last frame left a pyramid is the frame's flag (kFrameHizValid), not the recording's.
      push.drawCount |= gpu::kCullOcclusion;
    }
    const uint32_t drawCount = push.drawCount & gpu::kCullDrawCountMask;
    cmd.bindPipeline(pipelines.cull);
    cmd.push(push);
    cmd.dispatch((drawCount + FGB_VIS_CULL_GROUP_SIZE - 1) / FGB_VIS_CULL_GROUP_SIZE);
    cmd.computeBarrier();  // the arguments read every workgroup's count
    cmd.bindPipeline(pipelines.args);
    cmd.push(gpu::ArgsPush{push.counters, ctx.storageBufferIndex(args), FGB_VIS_RASTER_GROUP_SIZE, jobCapacity});
    cmd.dispatch(1);
  });
  node.recordingFixed();  // the frame's values, the HiZ flag included, come from its constants
}

// Phase 2 of render.occlusion: the clusters phase 1 held back, tested again against this frame's
// HiZ; those not hidden are appended to the visible list after phase 1's.
void VisBufferFeature::declareClusterCullLate(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("Cluster Cull (late)", graph::NodeType::Compute, kQueue);
  node.read(b.hiz, Access::StorageRead);
  node.read(b.candidates, Access::StorageRead);
  node.read(b.early.cullArgs, Access::StorageRead);
  b.late.counters = node.write(b.late.counters, Access::StorageReadWrite);
  b.visible = node.write(b.visible, Access::StorageReadWrite);
  b.late.cullArgs = node.write(b.late.cullArgs, Access::StorageReadWrite);  // see cullArgs in Cluster Cull
  gpu::LateCullPush push{};
  push.draws = b.push.draws;
  push.clusters = b.push.clusters;
  push.reversedZ = reversedZ_ ? 1u : 0u;
  node.setJob([push, pipelines = pipelines_, b, drawCount = drawCount_, jobCapacity = tileJobCapacity_,
               scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());
    push.hiz = ctx.storageBufferIndex(b.hiz);
    push.candidates = ctx.storageBufferIndex(b.candidates);
    push.earlyArgs = ctx.storageBufferIndex(b.early.cullArgs);
    push.counters = ctx.storageBufferIndex(b.late.counters);
    push.visible = ctx.storageBufferIndex(b.visible);
    cmd.bindPipeline(pipelines.cullLate);
    cmd.push(push);
    // Sized for every cluster (the candidate count is on the GPU); the invocations past it leave.
    cmd.dispatch((drawCount + FGB_VIS_CULL_GROUP_SIZE - 1) / FGB_VIS_CULL_GROUP_SIZE);
    cmd.computeBarrier();
    cmd.bindPipeline(pipelines.args);
    cmd.push(
        gpu::ArgsPush{push.counters, ctx.storageBufferIndex(b.late.cullArgs), FGB_VIS_RASTER_GROUP_SIZE, jobCapacity});
    cmd.dispatch(1);
  });
  node.recordingFixed();
}

void VisBufferFeature::declareTriangleFilter(graph::FrameGraph& graph, Buffers& b, VisPhase& phase) const {
  auto node =
      graph.addNode(std::string("Triangle Filter") + std::string(phase.suffix), graph::NodeType::Compute, kQueue);
  node.read(phase.cullArgs, Access::Indirect);
  node.read(phase.cullArgs, Access::StorageRead);
  node.read(b.visible, Access::StorageRead);
  phase.counters = node.write(phase.counters, Access::StorageReadWrite);
  b.smallList = node.write(b.smallList, Access::StorageWrite);
  b.largeList = node.write(b.largeList, Access::StorageWrite);
  b.tileJobs = node.write(b.tileJobs, Access::StorageWrite);
  phase.rasterArgs = node.write(phase.rasterArgs, Access::StorageReadWrite);  // see cullArgs in Cluster Cull
  node.setJob([push = b.push, pipelines = pipelines_, b, phase, scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());
    push.counters = ctx.storageBufferIndex(phase.counters);
    push.args = ctx.storageBufferIndex(phase.cullArgs);
    push.visible = ctx.storageBufferIndex(b.visible);
    push.smallList = ctx.storageBufferIndex(b.smallList);
    push.largeList = ctx.storageBufferIndex(b.largeList);
    push.tileJobs = ctx.storageBufferIndex(b.tileJobs);
    cmd.bindPipeline(pipelines.filter);
    cmd.push(push);
    cmd.dispatchIndirect(ctx.buffer(phase.cullArgs), kFilterArgsOffset);
    cmd.computeBarrier();
    cmd.bindPipeline(pipelines.args);
    cmd.push(gpu::ArgsPush{push.counters, ctx.storageBufferIndex(phase.rasterArgs), FGB_VIS_RASTER_GROUP_SIZE,
                           push.tileJobCapacity});
    cmd.dispatch(1);
  });
  node.recordingFixed();
}

void VisBufferFeature::declareRaster(graph::FrameGraph& graph, Buffers& b, const VisPhase& phase) const {
  auto node =
      graph.addNode(std::string("Visibility Raster") + std::string(phase.suffix), graph::NodeType::Compute, kQueue);
  node.read(phase.rasterArgs, Access::Indirect);
  node.read(phase.rasterArgs, Access::StorageRead);
  node.read(b.visible, Access::StorageRead);
  node.read(b.smallList, Access::StorageRead);
  node.read(b.largeList, Access::StorageRead);
  node.read(b.tileJobs, Access::StorageRead);
  b.writeWords(node, Access::StorageReadWrite);
  node.setJob([push = b.push, pipelines = pipelines_, b, args = phase.rasterArgs,
               scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());
    push.args = ctx.storageBufferIndex(args);
    push.visible = ctx.storageBufferIndex(b.visible);
    push.smallList = ctx.storageBufferIndex(b.smallList);
    push.largeList = ctx.storageBufferIndex(b.largeList);
    push.tileJobs = ctx.storageBufferIndex(b.tileJobs);
    push.words = b.wordsIndex(ctx);
    cmd.bindPipeline(pipelines.raster);
    cmd.push(push);
    cmd.dispatchIndirect(ctx.buffer(args), kSmallArgsOffset);
    // No barrier between the two: atomic max commutes. (A copy: the job runs every frame.)
    gpu::VisPush tiles = push;
    tiles.flags |= gpu::kFlagLargeTiles;
    cmd.push(tiles);
    cmd.dispatchIndirect(ctx.buffer(args), kTileArgsOffset);
  });
  node.recordingFixed();
}

// The HiZ pyramid of the depths phase 1 rasterised: phase 2 tests against it, and so does the next
// frame's phase 1. One build a frame, as niagara does: a pyramid without phase 2's depths is only
// farther where phase 2 drew, so the next frame holds back less there, never something visible. A
// second build after phase 2 cost more than the culling it won (H200, city walk at 1080p: frame
// median 0.805 -> 0.778 ms without it).
void VisBufferFeature::declareHizBuild(graph::FrameGraph& graph, Buffers& b) const {
  auto node = graph.addNode("HiZ Build", graph::NodeType::Compute, kQueue);
  b.readWords(node);
  b.hiz = node.write(b.hiz, Access::StorageReadWrite);  // each pass reads the level the one before wrote last
  const uint32_t passes = hizPasses(b.extent.width, b.extent.height);
  node.setJob([pipeline = pipelines_.hizBuild, b, passes](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    gpu::HizPush push{b.wordsIndex(ctx), ctx.storageBufferIndex(b.hiz), b.extent.width, b.extent.height, 0, 0, 0};
    cmd.bindPipeline(pipeline);
    for (uint32_t pass = 0; pass < passes; ++pass) {
      if (pass > 0) cmd.computeBarrier();
      push.sourceLevel = pass * FGB_HIZ_PASS_LEVELS;
      cmd.push(push);
      const HizGroups groups = hizPassGroups(b.extent.width, b.extent.height, pass);
      cmd.dispatch(groups.x, groups.y);
    }
  });
  node.recordingFixed();
}

// Material Shade also empties each word it read (the visibility buffer stays cleared between
// frames: no full-screen clear), and its first workgroup copies the culling counters to the host
// (statistics) with shader stores. A copy command in this node cost an H200 frame about 0.005 ms,
// and a node of its own between "Visibility Raster" and "Material Shade" more (H100: 5 us plus a
// ~20 us bubble).
void VisBufferFeature::declareShade(graph::FrameGraph& graph, Blackboard& board, Buffers& b) const {
  auto& targets = board.get<FrameTargets>();
  // The host reads the counters after the frame (addStats): before and after the graph, the
  // readback is in its hands.
  const graph::ImportState hostRead{graph::kStageHost, graph::kAccessHostRead, graph::Layout::Undefined,
                                    graph::QueueClass::Graphics};
  auto stats = graph.importBuffer("visibility stats readback", {2 * sizeof(VisCounters), {}},
                                  rhi::external(statsReadback_), hostRead, hostRead);
  auto node = graph.addNode("Material Shade", graph::NodeType::Compute, kQueue);
  b.writeWords(node, Access::StorageReadWrite);
  node.read(b.visible, Access::StorageRead);
  node.read(b.early.rasterArgs, Access::StorageRead);
  if (b.late.rasterArgs.valid()) node.read(b.late.rasterArgs, Access::StorageRead);
  stats = node.write(stats, Access::StorageWrite);
  b.depth = node.write(b.depth, Access::StorageWrite);
  targets.hdr = node.write(targets.hdr, Access::StorageWrite);
  const ClusteredLights clusters = readLightLists(node, board);
  // Shading pre-exposes what it writes, like every colour pass (auto exposure: this frame's state).
  if (targets.exposure.valid()) node.read(targets.exposure, Access::StorageRead);
  node.setJob([push = b.push, pipelines = pipelines_, b, hdr = targets.hdr, clusters, stats, scene = scene_,
               injectBias = injectBias_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());
    // As VisPush documents for this node: the phases' counters, and the host's copy.
    const uint32_t late = b.late.rasterArgs.valid() ? ctx.storageBufferIndex(b.late.rasterArgs) : gpu::kVisNoPhase;
    push.args = ctx.storageBufferIndex(b.early.rasterArgs) | late << 16;
    push.counters = ctx.storageBufferIndex(stats);
    push.words = b.wordsIndex(ctx);
    push.visible = ctx.storageBufferIndex(b.visible);
    push.depthOut = ctx.storageBufferIndex(b.depth);
    push.hdr = ctx.storageTextureIndex(hdr);
    if (injectBias) push.flags |= gpu::kFlagInjectBias;
    useLightLists(push, ctx, clusters);
    cmd.bindPipeline(pipelines.shade);
    cmd.push(push);
    cmd.dispatch((b.extent.width + FGB_VIS_SHADE_GROUP_SIZE - 1) / FGB_VIS_SHADE_GROUP_SIZE,
                 (b.extent.height + FGB_VIS_SHADE_GROUP_SIZE - 1) / FGB_VIS_SHADE_GROUP_SIZE);
  });
  node.recordingFixed();
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
  declareTriangleFilter(graph, b, b.early);
  declareRaster(graph, b, b.early);
  if (occlusion_) {
    declareHizBuild(graph, b);
    declareClusterCullLate(graph, b);
    declareTriangleFilter(graph, b, b.late);
    declareRaster(graph, b, b.late);
  }
  // The words as rasterised ("Material Shade" empties them).
  const VisibilityOutputs outputs{b.early.rasterArgs, b.late.rasterArgs, b.visible, b.words, b.wordImage};
  declareShade(graph, board, b);
  board.set(outputs);
}

void VisBufferFeature::addStats(std::map<std::string, double>& stats) const {
  if (!enabled()) return;
  VisCounters phases[2]{};
  std::memcpy(phases, device_->mapped(statsReadback_).data(), sizeof(phases));
  const VisCounters& early = phases[0];
  const VisCounters& late = phases[1];                     // zero without render.occlusion
  stats["vis_backing_image"] = imageBacking_ ? 1.0 : 0.0;  // render.vis_backing as run: 1 image, 0 buffer
  stats["vis_clusters"] = drawCount_;
  stats["vis_clusters_visible"] = double(early.visibleClusters) + late.visibleClusters;
  stats["vis_triangles_small"] = double(early.smallTriangles) + late.smallTriangles;
  stats["vis_triangles_large"] = double(early.largeTriangles) + late.largeTriangles;
  stats["vis_triangles_rasterised"] =
      double(early.smallTriangles) + early.largeTriangles + late.smallTriangles + late.largeTriangles;
  stats["vis_raster_tile_jobs"] = double(early.tileJobs) + late.tileJobs;
  // The LOD cut (render.lod_error): visible clusters per level (the last counts every level above).
  stats["vis_lod_threshold_px"] = lodThreshold_;
  for (uint32_t level = 0; level < FGB_VIS_LOD_STAT_LEVELS; ++level)
    stats["vis_lod_clusters_level" + std::to_string(level)] =
        double(early.lodClusters[level]) + late.lodClusters[level];
  stats["vis_large_overflow"] = double(early.overflow) + late.overflow;
  if (occlusion_) {
    // Two-phase occlusion (render.occlusion): held back by last frame's HiZ in phase 1, and of
    // those, found visible again against this frame's in phase 2.
    stats["vis_occlusion_phase1_occluded"] = early.occluded;
    stats["vis_occlusion_phase2_recovered"] = late.visibleClusters;
    stats["vis_occlusion_culled"] = double(early.occluded) - late.visibleClusters;
  }
}

}  // namespace fgb::features
