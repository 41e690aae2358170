// GPU particles (thesis): "Particle Emit" pops slots from a free list of a fixed-size pool,
// "Particle Update" ages/moves particles, pushes dead ones back and writes the indirect draw's
// instance count, "Particle Render" draws camera-facing quads alpha blended after opaque (depth-
// tested against the depth attachment, or on the visibility-buffer path by particle.frag against
// the opaque depth buffer: DepthTest).
// "Particle Reset" zeroes the draw's instance count in its own node (the thesis reset it inside the
// update shader behind a workgroup barrier, which does not order other workgroups).
// Deterministic by emitter seed and frame index (fixed 1/60 s step).
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class ParticleFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "particles"; }
  [[nodiscard]] bool enabled() const override { return poolSize_ > 0; }
  void configure(const GpuScene& scene);
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
  void addStats(std::map<std::string, double>& stats) const override;

 private:
  void createState(rhi::Device& device, const scene::Scene& scene, uint32_t seedOffset);

  rhi::Device* device_ = nullptr;
  const GpuScene* scene_ = nullptr;
  rhi::PipelineId emitPipeline_;
  rhi::PipelineId updatePipeline_;
  rhi::PipelineId renderPipeline_;
  rhi::BufferId pool_;        // Particle[poolSize] (persistent)
  rhi::BufferId freeList_;    // [0] count, [1..] free slots (persistent)
  rhi::BufferId emitters_;    // Emitter[] (static)
  rhi::BufferId quadIndices_; // 0 1 2 2 1 3
  rhi::BufferId argsTemplate_;                   // gpu::DrawCommand{6, 0, 0, 0, 0}
  DepthTest depthTest_ = DepthTest::Attachment;  // visibility buffer: particle.frag tests the opaque depth
  uint32_t poolSize_ = 0;
  uint32_t emitterCount_ = 0;
};

}  // namespace fgb::features
