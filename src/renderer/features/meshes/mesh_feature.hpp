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
// With the option "lod" (the visibility-buffer path, which uploads the clusters) and
// render.lod_error > 0, transparent instances draw their LOD cut instead of their index range:
// "Transparent Cluster Cull" (compute) keeps, per transparent instance in the frame's
// back-to-front order, the clusters of its mesh's DAG in the cut (the opaque clusters' rule:
// include/clusters.glsl) and inside the frustum, as one indexed draw each, packed in that order;
// "Mesh Render Transparent" issues them with one vkCmdDrawIndexedIndirectCount, so the blend
// order across instances is the sorted one. At render.lod_error=0 it draws the index range as
// without the option (full detail, the same image).
// With render.transparent=compute (or the option "transparent": "compute"; needs "lod" and the
// opaque depth buffer) the cut's cluster draws go to TransparentComputePasses
// (features/transparent_compute/: "Transparent Clear", "Transparent Raster", "Transparent Shade")
// instead, at render.lod_error=0 too (the cut is then level 0).
#pragma once

#include <vector>

#include "../context/render_feature.hpp"
#include "../transparent_compute/transparent_compute.hpp"
#include "renderer/shared/meshes.h"

namespace fgb::features {

// Visible-instance counts read back from the GPU (the last finished frame); the shaders index
// the words (mesh_cull.comp, mesh_compact.comp, transparent_cluster_pack.comp).
struct MeshCullStats {
  uint32_t instancesVisible = 0;
  uint32_t trianglesVisible = 0;
  uint32_t drawsIssued = 0;           // packed commands (groups with visible instances)
  uint32_t transparentTriangles = 0;  // of the visible transparent instances, full detail
  // The LOD cut of the transparent instances ("lod"): what "Mesh Render Transparent" drew, as
  // cluster draws and whole meshes (instances whose cut is level 0 throughout), and the triangles.
  uint32_t transparentClusters = 0;
  uint32_t transparentClusterTriangles = 0;
  uint32_t transparentWholeMeshes = 0;
  uint32_t reserved = 0;
};
static_assert(sizeof(MeshCullStats) == 32);

// What "Mesh Frustum Cull" writes and the draw nodes read.
struct MeshCullOutputs {
  graph::BufferHandle commands;    // per draw group (instance counts of visible instances)
  graph::BufferHandle drawList;    // packed commands of each batch, from its first group's index
  graph::BufferHandle drawCounts;  // packed commands per DrawClass
  graph::BufferHandle visible;     // visible instance ids, grouped by draw group
  graph::BufferHandle stats;       // MeshCullStats
};

// What "Transparent Cluster Cull" writes and "Mesh Render Transparent" draws (option "lod").
struct TransparentClusterDraws {
  graph::BufferHandle chunkCommands;  // per chunk: its kept draws, then zero draws (no draw count)
  graph::BufferHandle chunkTotals;    // uvec4 per chunk: kept draws, of which whole meshes, triangles
  graph::BufferHandle packed;         // every kept draw in blend order
  graph::BufferHandle drawCount;      // uint: draws in `packed`
  graph::BufferHandle dispatchArgs;   // render.transparent=compute: "Transparent Raster"'s indirect dispatch
};

class MeshFeature final : public IRenderFeature {
 public:
  // drawsOpaque, lod: the path's "opaque" and "lod" options; computeTransparent: its "transparent"
  // option is "compute" (feature_registry.cpp).
  explicit MeshFeature(bool drawsOpaque = true, bool lod = false, bool computeTransparent = false)
      : drawsOpaque_(drawsOpaque), lod_(lod), planComputeTransparent_(computeTransparent) {}
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
    rhi::PipelineId transparentCull;  // option "lod"
    rhi::PipelineId transparentPack;
  };

  MeshCullOutputs declareCull(graph::FrameGraph& graph);
  TransparentClusterDraws declareTransparentCull(graph::FrameGraph& graph, MeshCullOutputs& cull) const;
  void declareDepthPrepass(graph::FrameGraph& graph, Blackboard& board, const MeshCullOutputs& cull);
  void declareDraw(graph::FrameGraph& graph, Blackboard& board, std::vector<DrawClass> batches,
                   std::string_view nodeName, const MeshCullOutputs& cull);
  void declareTransparentClusterDraw(graph::FrameGraph& graph, Blackboard& board, const TransparentClusterDraws& draws);
  [[nodiscard]] gpu::ForwardPush forwardPush(std::string_view nodeName, bool transparent) const;

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
  // The option "lod"; transparentLod_: it applies (clusters uploaded, render.lod_error > 0).
  bool lod_ = false;
  bool transparentLod_ = false;
  float lodThreshold_ = 0.0f;       // scene pixels (render.lod_error x render.ssaa)
  uint32_t transparentChunks_ = 0;  // "Transparent Cluster Cull"'s workgroups (chunks of draws)
  // render.transparent (plan: the option "transparent"): computeTransparent_ where it applies
  // (option "lod", the opaque depth buffer): "Transparent Cluster Cull" in the cluster form at any
  // render.lod_error, then TransparentComputePasses instead of "Mesh Render Transparent".
  bool planComputeTransparent_ = false;
  bool computeTransparent_ = false;
  TransparentComputePasses transparentCompute_;
};

}  // namespace fgb::features
