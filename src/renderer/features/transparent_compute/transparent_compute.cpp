#include "transparent_compute.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>
#include <stdexcept>

#include "../context/handles.hpp"
#include "../visbuffer/visbuffer_feature.hpp"
#include "renderer/shared/transparent.h"

namespace fgb::features {
namespace {

using graph::Access;
constexpr graph::QueueClass kQueue = graph::QueueClass::Graphics;
constexpr uint64_t kCountersBytes = sizeof(gpu::TransparentCounters);
constexpr uint32_t kTile = FGB_TRANSPARENT_SHADE_GROUP_SIZE;

uint64_t shadeTiles(uint32_t width, uint32_t height) {
  return uint64_t{(width + kTile - 1) / kTile} * ((height + kTile - 1) / kTile);
}

// The K planes (uint64 per pixel each), then one uint64 flag per shade tile.
uint64_t kBufferBytes(uint32_t width, uint32_t height) {
  return uint64_t{8} * (uint64_t{FGB_TRANSPARENT_K} * width * height + shadeTiles(width, height));
}

// The tile list: its count, then one uint per tile.
uint64_t tileListBytes(uint32_t width, uint32_t height) {
  return uint64_t{4} * (1 + shadeTiles(width, height));
}

}  // namespace

struct TransparentComputePasses::PassBuffers {
  graph::BufferHandle words;         // the K-buffer and the tiles' flags (persistent)
  graph::BufferHandle counters;      // gpu::TransparentCounters, with the shade's dispatch
  graph::BufferHandle tiles;         // the tiles the raster listed for the shade
  graph::BufferHandle large;         // large triangles' fragment ids
  graph::BufferHandle draws;         // "Transparent Cluster Cull"'s packed cluster draws,
  graph::BufferHandle drawCount;     // their count,
  graph::BufferHandle dispatchArgs;  // and one raster workgroup per draw
};

void TransparentComputePasses::initialize(FeatureInit& init) {
  device_ = &init.device;
  scene_ = &init.scene;
  if (!init.device.shaderCapabilities().bufferInt64Atomics)
    throw DeviceError(
        "render.transparent=compute needs 64-bit storage-buffer atomics (shaderBufferInt64Atomics), which " +
        init.device.adapter().name + " lacks");
  // Large triangles are few: glass panes near the camera. A list overflow is rasterised by the
  // small path (slower, same image) and counted.
  largeCapacity_ = 65536;
  raster_ =
      init.device.createComputePipeline({"transparent raster", "renderer/transparent_compute/transparent_raster.comp"});
  shade_ =
      init.device.createComputePipeline({"transparent shade", "renderer/transparent_compute/transparent_shade.comp"});
  statsReadback_ = createReadbackBuffer(init.device, "transparent counters readback", kCountersBytes);
  kBufferBytes_ = kBufferBytes(init.settings.sceneWidth(), init.settings.sceneHeight());
  if (shadeTiles(init.settings.sceneWidth(), init.settings.sceneHeight()) >
      uint64_t{FGB_TRANSPARENT_SHADE_GROUPS_X} * FGB_TRANSPARENT_SHADE_GROUPS_X)
    throw std::logic_error("transparent shade tiles exceed two dispatch dimensions");
  kBuffer_ = init.device.createBuffer({"transparent k-buffer", kBufferBytes_,
                                       rhi::kBufferStorage | rhi::kBufferTransferDst, rhi::MemoryUsage::DeviceLocal});
}

void TransparentComputePasses::declare(graph::FrameGraph& graph, Blackboard& board, graph::BufferHandle draws,
                                       graph::BufferHandle drawCount, graph::BufferHandle dispatchArgs) const {
  auto& targets = board.get<FrameTargets>();
  if (!targets.opaqueDepth.valid())
    throw std::logic_error("render.transparent=compute before the opaque depth buffer (the visibility buffer's)");
  if (kBufferBytes(targets.extent.width, targets.extent.height) != kBufferBytes_)
    throw std::logic_error("the transparent K-buffer was sized for other scene passes");
  // Kept from frame to frame, empty between frames: "Transparent Shade" empties the slots it read.
  const graph::ImportState computeState{graph::kStageComputeShader,
                                        graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
                                        graph::Layout::Undefined, kQueue};
  PassBuffers b;
  b.words = graph.importBuffer("transparent k-buffer", {kBufferBytes_, {}}, rhi::external(kBuffer_), computeState,
                               computeState);
  b.counters = graph.createBuffer("transparent counters", {kCountersBytes, {}});
  b.large = graph.createBuffer("transparent large triangles", {uint64_t{4} * largeCapacity_, {}});
  b.tiles = graph.createBuffer("transparent tiles", {tileListBytes(targets.extent.width, targets.extent.height), {}});
  b.draws = draws;
  b.drawCount = drawCount;
  b.dispatchArgs = dispatchArgs;
  declareClear(graph, b);
  declareRaster(graph, targets, b);
  declareReadback(graph, "Transparent Stats Readback", b.counters, statsReadback_, "transparent counters readback",
                  kCountersBytes);
  declareShade(graph, board, b);
}

// The counters and the tile count zero every frame (the shade's dispatch: (0, 0, 1) workgroups);
// the K-buffer's slots and the tiles' flags empty (all ones: larger than any fragment's word) once,
// in the first recording: after it the shade leaves them empty (a fill of 8 K bytes a pixel every
// frame, 66 MB at 1920x1080, would cost more than the shade's stores to the pixels that had
// fragments).
void TransparentComputePasses::declareClear(graph::FrameGraph& graph, PassBuffers& b) const {
  auto clear = graph.addNode("Transparent Clear", graph::NodeType::Transfer, kQueue);
  b.words = clear.write(b.words, Access::TransferDst);
  b.counters = clear.write(b.counters, Access::TransferDst);
  b.tiles = clear.write(b.tiles, Access::TransferDst);
  clear.setJob([b, bytes = kBufferBytes_, emptied = kBufferEmptied_](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    if (!*emptied) cmd.fillBuffer(ctx.buffer(b.words), 0, bytes, 0xffffffffu);
    *emptied = true;
    constexpr uint64_t groupsZ = offsetof(gpu::TransparentCounters, shadeGroupsZ);
    static_assert(groupsZ + 4 == kCountersBytes);
    cmd.fillBuffer(ctx.buffer(b.counters), 0, groupsZ, 0);  // disjoint fills: no hazard between them
    cmd.fillBuffer(ctx.buffer(b.counters), groupsZ, 4, 1);
    cmd.fillBuffer(ctx.buffer(b.tiles), 0, 4, 0);  // the count; the raster writes the tiles below it
  });
  clear.recordingDependsOn([emptied = kBufferEmptied_] { return uint64_t{*emptied}; });
}

void TransparentComputePasses::declareRaster(graph::FrameGraph& graph, const FrameTargets& targets,
                                             PassBuffers& b) const {
  auto raster = graph.addNode("Transparent Raster", graph::NodeType::Compute, kQueue);
  raster.read(b.draws, Access::StorageRead);
  raster.read(b.drawCount, Access::StorageRead);
  raster.read(b.dispatchArgs, Access::Indirect);
  raster.read(targets.opaqueDepth, Access::StorageRead);
  b.words = raster.write(b.words, Access::StorageReadWrite);
  b.counters = raster.write(b.counters, Access::StorageReadWrite);
  b.large = raster.write(b.large, Access::StorageWrite);  // appended by the first dispatch, read by the second
  b.tiles = raster.write(b.tiles, Access::StorageReadWrite);  // appends to the count Clear zeroed
  gpu::VisPush push = visScenePush(*device_, *scene_);
  push.largeCapacity = largeCapacity_;
  raster.setJob([push, pipeline = raster_, b, opaqueDepth = opaqueDepthSource(targets, DepthTest::OpaqueDepthBuffer),
                 scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());  // also the lights, which the raster does not read
    push.draws = ctx.storageBufferIndex(b.draws);
    push.args = ctx.storageBufferIndex(b.drawCount);
    push.counters = ctx.storageBufferIndex(b.counters);
    push.largeList = ctx.storageBufferIndex(b.large);
    push.words = ctx.storageBufferIndex(b.words);
    push.tileJobs = ctx.storageBufferIndex(b.tiles);
    const gpu::OpaqueDepthTest test = opaqueDepth.push(ctx);
    push.depthOut = test.depths;
    push.depthCompare = test.compareOp;
    cmd.bindPipeline(pipeline);
    cmd.push(push);
    cmd.dispatchIndirect(ctx.buffer(b.dispatchArgs));  // one workgroup per kept draw
    cmd.computeBarrier();                              // the large list and its count, complete
    gpu::VisPush largePass = push;
    largePass.flags |= gpu::kFlagLargeTiles;
    cmd.push(largePass);
    cmd.dispatch(FGB_TRANSPARENT_LARGE_GROUPS);
  });
  raster.recordingFixed();
}

void TransparentComputePasses::declareShade(graph::FrameGraph& graph, Blackboard& board, PassBuffers& b) const {
  auto& targets = board.get<FrameTargets>();
  auto shade = graph.addNode("Transparent Shade", graph::NodeType::Compute, kQueue);
  b.words = shade.write(b.words, Access::StorageReadWrite);  // reads the slots, empties them and the tiles' flags
  shade.read(b.draws, Access::StorageRead);
  shade.read(b.counters, Access::Indirect);  // one workgroup per listed tile
  shade.read(b.tiles, Access::StorageRead);
  targets.hdr = shade.write(targets.hdr, Access::StorageReadWrite);
  const ClusteredLights clusters = readLightLists(shade, board);
  if (targets.exposure.valid()) shade.read(targets.exposure, Access::StorageRead);  // pre-exposure
  shade.setJob([push = visScenePush(*device_, *scene_), pipeline = shade_, b, hdr = targets.hdr, clusters,
                scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    useFrame(push, *scene, ctx.execution());
    push.draws = ctx.storageBufferIndex(b.draws);
    push.words = ctx.storageBufferIndex(b.words);
    push.tileJobs = ctx.storageBufferIndex(b.tiles);
    push.hdr = ctx.storageTextureIndex(hdr);
    useLightLists(push, ctx, clusters);
    cmd.bindPipeline(pipeline);
    cmd.push(push);
    cmd.dispatchIndirect(ctx.buffer(b.counters), offsetof(gpu::TransparentCounters, shadeGroupsX));
  });
  shade.recordingFixed();
  targets.color = targets.hdr;  // single-sampled: later colour passes load the blended image
}

void TransparentComputePasses::addStats(std::map<std::string, double>& stats) const {
  gpu::TransparentCounters read{};
  std::memcpy(&read, device_->mapped(statsReadback_).data(), sizeof(read));
  stats["transparent_fragments_inserted"] = read.inserted;
  stats["transparent_fragments_dropped"] = read.dropped;
  stats["transparent_large_triangles"] = read.largeTriangles;
  stats["transparent_large_overflow"] = read.largeOverflow;
  stats["transparent_tiles_shaded"] = read.tilesListed;
}

}  // namespace fgb::features
