// The visibility-buffer path (render.path=visbuffer, issue 18): the opaque and alpha-masked scene
// is culled, rasterised and shaded in compute instead of "Mesh Render".
//   "Visibility Clear"          zeroes the culling counters (the visibility buffer persists, empty
//                               between frames: zeroed once at start, then "Material Shade" empties
//                               each word it reads);
//   "Cluster Cull"              instances + clusters: the LOD cut (render.lod_error, where the
//                               path's plan has "lod": every level's clusters are candidates, one
//                               consistent cut of each instance's DAG is kept), frustum, backface cone;
//   "Triangle Filter"           per triangle: degenerate, behind the eye, outside the frustum,
//                               back-facing, covers no pixel centre; writes the small and large
//                               triangle lists and the raster's indirect arguments;
//   "Visibility Raster"         64-bit atomic max of (depth, id) per pixel (storage buffer, or R64
//                               image with 64-bit image atomics: render.vis_backing);
//   with render.occlusion=1 (two-phase HiZ occlusion culling), "Cluster Cull" also holds back the
//   clusters hidden behind last frame's HiZ pyramid (a persistent buffer), then
//   "HiZ Build"                 the pyramid of the depths phase 1 rasterised;
//   "Cluster Cull (late)"       the held-back clusters against it: the visible ones go through
//   "Triangle Filter (late)", "Visibility Raster (late)" (counters of their own); the next
//                               frame's phase 1 tests against this frame's pyramid (one build);
//   "Material Shade"            rebuilds each pixel's triangle, shades it like forward.frag (shared
//                               include) into the HDR target, writes the pixel depths into
//                               "visibility depth" (FrameTargets::opaqueDepth), against which the
//                               colour passes that follow (transparent meshes, particles) depth-test
//                               in their fragment shaders (no depth attachment on this path), empties
//                               the words, and copies the culling counters to the host (statistics).
// Culling outputs are published on the blackboard (VisibilityOutputs).
#pragma once

#include "../context/render_feature.hpp"
#include "renderer/shared/visbuffer.h"

namespace fgb::features {

struct VisPhase;  // one culling phase's counters (visbuffer_feature.cpp)

// The push fields every node taking gpu::VisPush shares (the scene's cluster geometry, vertex
// streams, materials; reversed Z, CPU device); the nodes fill in their own buffers. Also the
// compute transparent passes' (features/transparent_compute/).
[[nodiscard]] gpu::VisPush visScenePush(rhi::Device& device, const GpuScene& scene);

// Published by the visibility-buffer feature for later nodes (debug views, statistics).
struct VisibilityOutputs {
  graph::BufferHandle counters;         // VisCounters after "Triangle Filter"
  graph::BufferHandle lateCounters;     // after "Triangle Filter (late)" (render.occlusion only)
  graph::BufferHandle visibleClusters;  // ClusterDraw indices that passed "Cluster Cull"
  // uint64 per pixel, depth key << 32 | id (render.vis_backing): a row-major storage buffer, or an
  // R64Uint storage texture. Exactly one of the two is valid.
  graph::BufferHandle visibility;
  graph::TextureHandle visibilityImage;
};

class VisBufferFeature final : public IRenderFeature {
 public:
  // lod: the path's plan draws the LOD cut of render.lod_error (else level 0, full detail).
  explicit VisBufferFeature(bool lod) : lod_(lod) {}
  [[nodiscard]] std::string_view name() const override { return "visbuffer"; }
  [[nodiscard]] bool enabled() const override { return drawCount_ > 0; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
  void addStats(std::map<std::string, double>& stats) const override;

 private:
  struct Pipelines {
    rhi::PipelineId cull;
    rhi::PipelineId args;
    rhi::PipelineId filter;
    rhi::PipelineId raster;
    rhi::PipelineId shade;
    rhi::PipelineId clearImage;  // image backing only
    rhi::PipelineId cullLate;    // render.occlusion only
    rhi::PipelineId hizBuild;    // render.occlusion only
  };
  struct Buffers;

  Buffers declareBuffers(graph::FrameGraph& graph, const FrameTargets& targets) const;
  [[nodiscard]] graph::ImportState wordsState() const;
  void clearWordsOnce(rhi::Device& device) const;
  static void declareClear(graph::FrameGraph& graph, Buffers& buffers);
  void declareClusterCull(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareClusterCullLate(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareTriangleFilter(graph::FrameGraph& graph, Buffers& buffers, VisPhase& phase) const;
  void declareRaster(graph::FrameGraph& graph, Buffers& buffers, const VisPhase& phase) const;
  void declareHizBuild(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareShade(graph::FrameGraph& graph, Blackboard& board, Buffers& buffers) const;

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  Pipelines pipelines_;
  rhi::BufferId statsReadback_;
  // The visibility words (render.vis_backing: one of the two), kept from frame to frame.
  rhi::BufferId words_;
  rhi::TextureId wordImage_;
  graph::Extent wordsExtent_;
  uint32_t drawCount_ = 0;
  uint32_t largeCapacity_ = 0;
  uint32_t tileJobCapacity_ = 0;
  bool reversedZ_ = false;
  bool injectBias_ = false;         // debug.inject_bias=Material Shade
  bool imageBacking_ = false;       // render.vis_backing resolved to image
  bool occlusion_ = false;          // render.occlusion
  bool occlusionHoldBack_ = false;  // debug.occlusion_hold_back (with render.occlusion)
  bool lod_ = true;                 // the path's "lod" option
  float lodThreshold_ = 0.0f;       // scene pixels; 0: level 0 only
  rhi::BufferId hiz_;               // the HiZ pyramid, kept from frame to frame (render.occlusion)
  uint64_t hizKeys_ = 0;            // its size in 32-bit depth keys
};

}  // namespace fgb::features
