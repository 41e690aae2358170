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
//                            passes after it test as on forward ("depth_test": "attachment").
// render.occlusion has no effect on this path (as on forward); its statistics are meshlet_*.
#pragma once

#include "../context/render_feature.hpp"

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
  };

  void declareReset(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareInstanceCull(graph::FrameGraph& graph, Buffers& buffers) const;
  void declareRender(graph::FrameGraph& graph, Blackboard& board, Buffers& buffers) const;

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  rhi::PipelineId cull_;
  rhi::PipelineId render_;
  rhi::BufferId statsReadback_;
  uint32_t drawCount_ = 0;     // cluster draws (every level of every opaque or masked instance)
  uint32_t meshFlags_ = 0;     // gpu::MeshletPush::flags: the sample count, small-triangle culling
  float lodThreshold_ = 0.0f;  // scene pixels; 0: level 0 only
  bool lod_ = true;            // the path's "lod" option
  bool injectNan_ = false;     // debug.inject_nan names "Meshlet Render"
};

}  // namespace fgb::features
