// The mesh-shader path (render.path=meshlet, issue 28): the opaque and alpha-masked scene drawn
// from the cooked clusters by task and mesh shaders, rasterised by the hardware with MSAA 1-8 and
// shaded by forward.frag (the same shading as forward's "Mesh Render").
//   "Meshlet Reset"          zeroes the task-draw count and the statistics;
//   "Meshlet Instance Cull"  (compute) one task draw per instance whose box meets the frustum;
//   "Meshlet Render"         (graphics) drawMeshTasksIndirectCount over those draws: the task
//                            shader culls each cluster ("Cluster Cull"'s tests, include/clusters.glsl:
//                            LOD cut, frustum sphere, normal cone), the mesh shader culls triangles
//                            (niagara's: back-facing, zero area, no sample covered, outside the
//                            frustum's sides) and writes the depth attachment, which the colour
//                            passes after it test as on forward ("depth_test": "attachment");
//   with render.occlusion=1 at MSAA 1 (two-phase HiZ occlusion culling, as on the visbuffer path),
//   "Meshlet Render" holds back the clusters hidden behind last frame's HiZ pyramid (a persistent
//   buffer), then
//   "HiZ Build"              the pyramid of phase 1's depth attachment, and phase 2's arguments;
//   "Meshlet Render (late)"  the held-back clusters this frame's pyramid does not hide;
//   "HiZ Build (late)"       the pyramid of the whole frame, for the next frame's phase 1.
// With MSAA > 1 render.occlusion has no effect here (the pyramid reads a single-sampled depth).
// Statistics: meshlet_*.
#pragma once

#include "../context/render_feature.hpp"
#include "renderer/shared/meshlets.h"

namespace fgb::features {

class MeshletFeature final : public IRenderFeature {
 public:
  // lod: the path's plan draws the LOD cut of render.lod_error (else level 0, full detail).
  explicit MeshletFeature(bool lod) : lod_(lod) {}
  [[nodiscard]] std::string_view name() const override { return "meshlets"; }
  [[nodiscard]] bool enabled() const override { return drawCount_ > 0; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
  void addStats(std::map<std::string, double>& stats) const override;

 private:
  struct Buffers {
    graph::BufferHandle commands;  // draw count header + gpu::MeshletTaskCommand per visible instance
    graph::BufferHandle stats;     // gpu::MeshletStats
    // render.occlusion only:
    graph::BufferHandle hiz;           // the HiZ pyramid (persistent)
    graph::BufferHandle candidates;    // count, then the ClusterDraw indices phase 1 held back
    graph::BufferHandle lateCommands;  // draw count header + one task draw over the candidates
  };

  [[nodiscard]] gpu::MeshletPush scenePush() const;
  void declareReset(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareInstanceCull(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareRender(graph::FrameGraph& graph, Blackboard& board, Buffers& buffers, bool late) const;
  void declareHizBuild(graph::FrameGraph& graph, FrameTargets& targets, Buffers& buffers, bool late) const;

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  rhi::PipelineId cull_;
  rhi::PipelineId render_;
  rhi::PipelineId hizBuild_;  // render.occlusion only
  rhi::PipelineId lateArgs_;  // render.occlusion only
  rhi::BufferId hiz_;         // the HiZ pyramid, kept from frame to frame (render.occlusion)
  uint64_t hizKeys_ = 0;      // its size in 32-bit depth keys
  rhi::BufferId statsReadback_;
  uint32_t drawCount_ = 0;     // cluster draws (every level of every opaque or masked instance)
  uint32_t meshFlags_ = 0;     // gpu::MeshletPush::flags: the sample count, small-triangle culling
  float lodThreshold_ = 0.0f;  // scene pixels; 0: level 0 only
  bool lod_ = true;            // the path's "lod" option
  bool injectNan_ = false;     // debug.inject_nan names "Meshlet Render"
  bool injectBias_ = false;    // debug.inject_bias names "Meshlet Render"
  bool occlusion_ = false;     // render.occlusion at MSAA 1
};

}  // namespace fgb::features
