#include "clustered_lighting.hpp"

#include "../context/handles.hpp"
#include "renderer/shared/lighting.h"

#include <fgb/rhi/job_context.hpp>

#include <algorithm>
#include <array>
#include <cstring>

namespace fgb::features {
namespace {

using graph::Access;

// The bounds buffer is written by compute and read by compute, frame after frame: it stays on the
// compute queue (no ownership transfer in or out of the graph).
constexpr graph::ImportState kBoundsState{graph::kStageComputeShader,
                                          graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
                                          graph::Layout::Undefined, graph::QueueClass::Compute};

// "Clustered Light Cull"'s workgroups: one per FGB_LIGHT_CULL_BLOCK^2 tiles of a depth slice.
std::array<uint32_t, 3> cullGroups(const glm::uvec4& grid) {
  constexpr uint32_t kBlock = FGB_LIGHT_CULL_BLOCK;
  return {(grid.x + kBlock - 1) / kBlock, (grid.y + kBlock - 1) / kBlock, grid.z};
}

}  // namespace

void ClusteredLighting::initialize(FeatureInit& init) {
  configure(init.scene);
  clustered_ = init.settings.lightingMode == LightingMode::Clustered;
  dropLight_ = init.settings.dropLight;
  device_ = &init.device;
  scene_ = &init.scene;
  if (!enabled()) return;
  const auto& grid = init.scene.constants.clusterGrid;
  clusterCount_ = grid.x * grid.y * grid.z;
  capacity_ = std::min<uint32_t>(init.settings.maxLightsPerCluster, FGB_MAX_LIGHTS_PER_CLUSTER);
  boundsPipeline_ = init.device.createComputePipeline({"cluster bounds", "renderer/cluster_bounds.comp"});
  cullPipeline_ = init.device.createComputePipeline({"clustered light cull", "renderer/light_cull.comp"});
  bounds_ = init.device.createBuffer(
      {"cluster bounds", uint64_t{32} * clusterCount_, rhi::kBufferStorage, rhi::MemoryUsage::DeviceLocal});
  const std::array<uint32_t, 3> groups = cullGroups(grid);
  cullGroups_ = groups[0] * groups[1] * groups[2];
  // Written by the cull shader itself (statistics), a row per workgroup: a storage buffer the host reads.
  statsReadback_ = init.device.createBuffer(
      {"light cull stats readback", statsBytes(), rhi::kBufferStorage, rhi::MemoryUsage::Readback});
  std::memset(init.device.mapped(statsReadback_).data(), 0, statsBytes());
}

graph::BufferHandle ClusteredLighting::declareBounds(graph::FrameGraph& graph) {
  auto bounds = graph.importBuffer("cluster bounds", {uint64_t{32} * clusterCount_, {}}, rhi::external(bounds_),
                                   kBoundsState, kBoundsState);
  auto node = graph.addNode("Cluster Bounds", graph::NodeType::Compute);
  bounds = node.write(bounds, Access::StorageReadWrite);  // read-write: contents kept when not rebuilt
  gpu::ClusterBoundsPush push{0, device_->storageBufferIndex(bounds_), clusterCount_};
  // The bounds depend on the projection only: rebuilt when the frame's differs from the one they
  // were built for (a camera path that changes the field of view), so this recording depends on it.
  node.setJob([push, pipeline = boundsPipeline_, state = boundsState_, scene = scene_](
                  graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    const glm::mat4& projection = scene->current.proj;
    if (state->built && state->builtFor == projection) return;  // projection unchanged: keep bounds
    push.frame = scene->frame(ctx.execution()).constantsIndex;
    auto& cmd = ctx.cmd();
    cmd.bindPipeline(pipeline);
    cmd.push(push);
    cmd.dispatch((push.clusterCount + FGB_CLUSTER_BOUNDS_GROUP_SIZE - 1) / FGB_CLUSTER_BOUNDS_GROUP_SIZE);
    state->built = true;
    state->builtFor = projection;
  });
  node.recordingDependsOn([state = boundsState_, projection = scene_->constants.proj] {
    return static_cast<uint64_t>(state->built && state->builtFor == projection);  // what the job tests
  });
  return bounds;
}

void ClusteredLighting::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  const auto bounds = declareBounds(graph);
  ClusteredLights lists;
  lists.counts = graph.createBuffer("cluster light counts", {uint64_t{4} * clusterCount_, {}});
  lists.indices = graph.createBuffer("cluster light indices", {uint64_t{4} * clusterCount_ * capacity_, {}});

  // The host reads the counts after the frame (addStats): before and after the graph, the
  // readback is in the host's hands.
  const graph::ImportState hostRead{graph::kStageHost, graph::kAccessHostRead, graph::Layout::Undefined,
                                    graph::QueueClass::Graphics};
  auto statsToHost = graph.importBuffer("light cull stats readback", {statsBytes(), {}}, rhi::external(statsReadback_),
                                        hostRead, hostRead);

  auto node = graph.addNode("Clustered Light Cull", graph::NodeType::Compute);
  node.read(bounds, Access::StorageRead);
  lists.counts = node.write(lists.counts, Access::StorageWrite);
  lists.indices = node.write(lists.indices, Access::StorageWrite);
  statsToHost = node.write(statsToHost, Access::StorageWrite);
  gpu::LightCullPush push{0, device_->storageBufferIndex(bounds_), 0, 0, 0, dropLight_, 0, 0};
  const std::array<uint32_t, 3> groups = cullGroups(scene_->constants.clusterGrid);
  node.setJob(
      [push, pipeline = cullPipeline_, lists, statsToHost, groups, scene = scene_](graph::JobContext& context) mutable {
        auto& ctx = rhi::rhiContext(context);
        const FrameBuffers& frame = scene->frame(ctx.execution());
        push.frame = frame.constantsIndex;
        push.lights = frame.lightsIndex;
        push.counts = ctx.storageBufferIndex(lists.counts);
        push.indices = ctx.storageBufferIndex(lists.indices);
        push.statsToHost = ctx.storageBufferIndex(statsToHost);
        ctx.cmd().bindPipeline(pipeline);
        ctx.cmd().push(push);
        ctx.cmd().dispatch(groups[0], groups[1], groups[2]);  // one invocation per cluster
      });
  node.recordingFixed();
  board.set(lists);
}

void ClusteredLighting::addStats(std::map<std::string, double>& stats) const {
  stats["clusters"] = clusterCount_;
  if (!enabled() || clusterCount_ == 0) return;
  std::vector<uint32_t> rows(size_t{cullGroups_} * FGB_LIGHT_CULL_STATS);
  std::memcpy(rows.data(), device_->mapped(statsReadback_).data(), statsBytes());
  uint64_t sum = 0;
  uint32_t max = 0;
  uint64_t overflowed = 0;
  for (size_t row = 0; row < rows.size(); row += FGB_LIGHT_CULL_STATS) {
    sum += rows[row];
    max = std::max(max, rows[row + 1]);
    overflowed += rows[row + 2];
  }
  stats["lights_per_cluster_avg"] = double(sum) / double(clusterCount_);
  stats["lights_per_cluster_max"] = max;
  stats["clusters_overflowed"] = overflowed;
}

}  // namespace fgb::features
