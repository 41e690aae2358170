// GPU-driven static meshes: "Mesh Frustum Cull" (compute) fills indirect commands grouped per mesh
// and counts visible instances/triangles, then (second dispatch, after a barrier inside the node)
// packs the groups that have visible instances into one command list per batch with its count;
// "Mesh Render" issues one indirect multi-draw per material batch (opaque, alpha-masked) with the
// GPU-written count (vkCmdDrawIndexedIndirectCount; where the device lacks it, every group's
// command, empty ones included), and "Mesh Render Transparent" draws blended instances back to
// front after opaque. With render.depth_prepass=1, "Depth Prepass" lays down the depth of opaque
// instances first (alpha-masked ones write depth in "Mesh Render"). Command instance counts are
// reset by their own transfer node ("Mesh Cull Reset") so no shader relies on cross-workgroup
// ordering. With the option "opaque": false (the visibility-buffer path) only "Mesh Render
// Transparent" is declared (with the cull it needs), which depth-tests as the path says: there in
// its fragment shader against the opaque depth buffer "Material Shade" wrote (no depth attachment:
// DepthTest::OpaqueDepthBuffer); the opaque scene is the visbuffer feature's.
#pragma once

#include "../context/render_feature.hpp"

#include <vector>

namespace fgb::features {

// Visible-instance counts read back from the GPU (the last finished frame).
struct MeshCullStats {
  uint32_t instancesVisible = 0;
  uint32_t trianglesVisible = 0;
  uint32_t drawsIssued = 0;  // packed commands (groups with visible instances)
};

// What "Mesh Frustum Cull" writes and the draw nodes read.
struct MeshCullOutputs {
  graph::BufferHandle commands;    // per draw group (instance counts of visible instances)
  graph::BufferHandle drawList;    // packed commands of each batch, from its first group's index
  graph::BufferHandle drawCounts;  // packed commands per DrawClass
  graph::BufferHandle visible;     // visible instance ids, grouped by draw group
  graph::BufferHandle stats;       // MeshCullStats
};

class MeshFeature final : public IRenderFeature {
 public:
  // drawsOpaque: the path's "opaque" option (feature_registry.cpp).
  explicit MeshFeature(bool drawsOpaque = true) : drawsOpaque_(drawsOpaque) {}
  [[nodiscard]] std::string_view name() const override { return "meshes"; }
  [[nodiscard]] bool enabled() const override { return instanceCount_ > 0 && (drawsOpaque_ || hasTransparent_); }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
  void addStats(std::map<std::string, double>& stats) const override;

  // Must be called before initialize() to know enabled() (from the uploaded scene).
  void configure(const GpuScene& scene);

 private:
  struct Pipelines {
    rhi::PipelineId cull;
    rhi::PipelineId compact;
    rhi::PipelineId opaque;
    rhi::PipelineId transparent;
    rhi::PipelineId depthOnly;
  };

  MeshCullOutputs declareCull(graph::FrameGraph& graph);
  void declareDepthPrepass(graph::FrameGraph& graph, Blackboard& board, const MeshCullOutputs& cull);
  void declareDraw(graph::FrameGraph& graph, Blackboard& board, std::vector<DrawClass> batches,
                   std::string_view nodeName, const MeshCullOutputs& cull);

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  Pipelines pipelines_;
  rhi::BufferId statsReadback_;
  uint32_t instanceCount_ = 0;
  bool hasTransparent_ = false;
  bool depthPrepass_ = false;
  std::string injectNanPass_;  // debug.inject_nan
  std::string injectBiasPass_;  // debug.inject_bias
  // "Mesh Render" draws opaque and masked instances (option "opaque"). The visibility-buffer path
  // draws those in compute and leaves this feature only the transparent ones.
  bool drawsOpaque_ = true;
  // How "Mesh Render Transparent" tests the opaque depth (the path's depth_test; visibility
  // buffer: in forward.frag).
  DepthTest transparentDepthTest_ = DepthTest::Attachment;
  bool drawCount_ = false;  // the device has vkCmdDrawIndexedIndirectCount
};

}  // namespace fgb::features
