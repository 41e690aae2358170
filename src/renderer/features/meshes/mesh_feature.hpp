// GPU-driven static meshes: "Mesh Frustum Cull" (compute) fills indirect commands grouped per mesh
// and counts visible instances/triangles; "Mesh Render" issues one indirect multi-draw per
// pipeline batch (opaque, alpha-masked) and "Mesh Render Transparent" draws blended instances
// back to front after opaque. With render.depth_prepass=1, "Depth Prepass" lays down the depth of
// opaque instances first (alpha-masked ones write depth in "Mesh Render"). Command instance counts are reset by their own transfer node
// ("Mesh Cull Reset") so no shader relies on cross-workgroup ordering.
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

// Visible-instance counts read back from the GPU (the last finished frame).
struct MeshCullStats {
  uint32_t instancesVisible = 0;
  uint32_t trianglesVisible = 0;
};

class MeshFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "meshes"; }
  [[nodiscard]] bool enabled() const override { return instanceCount_ > 0; }
  [[nodiscard]] uint32_t colorPasses() const override { return hasTransparent_ ? 2 : 1; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
  void addStats(std::map<std::string, double>& stats) const override;

  // Must be called before initialize() to know enabled()/colorPasses() (from the uploaded scene).
  void configure(const GpuScene& scene);

 private:
  struct Pipelines {
    rhi::PipelineId cull;
    rhi::PipelineId opaque;
    rhi::PipelineId transparent;
    rhi::PipelineId depthOnly;
  };

  void declareCull(graph::FrameGraph& graph, graph::BufferHandle& commands, graph::BufferHandle& visible,
                   graph::BufferHandle& stats);
  void declareDepthPrepass(graph::FrameGraph& graph, Blackboard& board, graph::BufferHandle commands,
                           graph::BufferHandle visible);
  void declareStatsReadback(graph::FrameGraph& graph, graph::BufferHandle stats);
  void declareDraw(graph::FrameGraph& graph, Blackboard& board, DrawClass firstClass, DrawClass lastClass,
                   std::string_view nodeName, graph::BufferHandle commands, graph::BufferHandle visible);

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  Pipelines pipelines_;
  rhi::BufferId statsReadback_;
  uint32_t instanceCount_ = 0;
  bool hasTransparent_ = false;
  bool depthPrepass_ = false;
};

}  // namespace fgb::features
