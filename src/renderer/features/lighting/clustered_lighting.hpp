// Clustered light culling (thesis): "Cluster Bounds" rebuilds the clusters' view-space AABBs only
// when the projection changes (a persistent buffer); "Clustered Light Cull" fills per-cluster light
// lists that the forward passes read (published as ClusteredLights), culling in two levels: each
// light against the union box of 8x8 tiles of one slice, then the survivors against each cluster's
// box (light_cull.comp; the lists are exactly the per-cluster test's, in light order). A scene
// without point lights declares none of this, nor does lighting.mode=all (forward shading then
// evaluates every light for every fragment, with no per-cluster cap: the reference). Stats:
// average/max lights per cluster (read back every frame).
#pragma once

#include <memory>

#include "../context/render_feature.hpp"
#include "renderer/shared/lighting.h"

namespace fgb::features {

class ClusteredLighting final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "clustered lighting"; }
  // lighting.mode=all: no cluster passes; the forward passes then loop over every light.
  [[nodiscard]] bool enabled() const override { return lightCount_ > 0 && clustered_; }
  void configure(const GpuScene& scene) { lightCount_ = scene.lightCount; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
  void addStats(std::map<std::string, double>& stats) const override;

 private:
  // The projection the bounds buffer was last built for, shared with the job across executions.
  struct BoundsState {
    glm::mat4 builtFor{0.0f};
    bool built = false;
  };

  graph::BufferHandle declareBounds(graph::FrameGraph& graph);

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  rhi::PipelineId boundsPipeline_;
  rhi::PipelineId cullPipeline_;
  rhi::BufferId bounds_;         // persistent: vec4 min, max per cluster
  rhi::BufferId statsReadback_;  // per light-cull workgroup a row of FGB_LIGHT_CULL_STATS uints
  uint32_t cullGroups_ = 0;
  uint64_t statsBytes() const { return uint64_t{4} * FGB_LIGHT_CULL_STATS * cullGroups_; }
  std::shared_ptr<BoundsState> boundsState_ = std::make_shared<BoundsState>();
  uint32_t lightCount_ = 0;
  bool clustered_ = true;
  uint32_t clusterCount_ = 0;
  uint32_t dropLight_ = 0;  // debug.drop_light (LightCullPush::dropLight)
  uint32_t capacity_ = 0;
};

}  // namespace fgb::features
