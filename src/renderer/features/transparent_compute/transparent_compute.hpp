// The visibility-buffer path's transparent meshes in compute (render.transparent=compute; the
// meshes feature owns them and declares these nodes in place of "Mesh Render Transparent"): from
// "Transparent Cluster Cull"'s kept cluster draws (cluster form, kTransparentCullClusterIds),
//   "Transparent Clear"  (transfer) zeroes the counters and the tile list (and, in its first
//                        recording, empties the K-buffer and its tile flags, which persist: the
//                        shade empties what it read);
//   "Transparent Raster" keeps, per pixel, the FGB_TRANSPARENT_K nearest fragments in front of the
//                        opaque depth (64-bit atomicMin cascade; small triangles one invocation
//                        each, large ones shared by a workgroup), listing each 8x8 tile a
//                        fragment lands in once;
//   "Transparent Shade"  (indirect, one workgroup per listed tile) shades each kept fragment as "Material Shade" shades
//   an opaque pixel and
//                        blends them far to near over the HDR image (the raster pass's blend).
// Per-pixel sorting blends overlapping instances, and an instance's own layers, in depth order,
// where the raster pass blends instances back to front by their centres and an instance's
// triangles in index order. Shaders: shaders/renderer/transparent_compute/; shared constants:
// renderer/shared/transparent.h.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "../context/render_feature.hpp"

namespace fgb::features {

class TransparentComputePasses {
 public:
  void initialize(FeatureInit& init);
  // After the opaque scene (FrameTargets::opaqueDepth written); draws, drawCount, dispatchArgs:
  // "Transparent Cluster Cull"'s packed cluster draws, their count, and one workgroup per draw as
  // indirect dispatch arguments. Writes FrameTargets::hdr (and color).
  void declare(graph::FrameGraph& graph, Blackboard& board, graph::BufferHandle draws, graph::BufferHandle drawCount,
               graph::BufferHandle dispatchArgs) const;
  void addStats(std::map<std::string, double>& stats) const;

 private:
  struct PassBuffers;  // one frame's buffers of the three nodes (transparent_compute.cpp)
  void declareClear(graph::FrameGraph& graph, PassBuffers& b) const;
  void declareRaster(graph::FrameGraph& graph, const FrameTargets& targets, PassBuffers& b) const;
  void declareShade(graph::FrameGraph& graph, Blackboard& board, PassBuffers& b) const;

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  rhi::PipelineId raster_;
  rhi::PipelineId shade_;
  rhi::BufferId statsReadback_;
  uint32_t largeCapacity_ = 0;
  rhi::BufferId kBuffer_;  // persistent, empty between frames; the tiles' flags after the slots
  uint64_t kBufferBytes_ = 0;
  // Whether a recording of "Transparent Clear" has emptied kBuffer_ (the first one does).
  std::shared_ptr<bool> kBufferEmptied_ = std::make_shared<bool>(false);
};

}  // namespace fgb::features
