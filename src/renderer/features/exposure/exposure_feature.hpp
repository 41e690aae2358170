// "Exposure" (post.exposure=auto): measures the frame's log-average luminance on the GPU (a
// two-dispatch compute reduction over the pre-exposed HDR image) and updates the exposure state
// (gpu::Exposure): exposure = key / L_avg with key 0.18, applied by this frame's tone mapping and used
// as the next frame's pre-exposure. No temporal adaptation: the exposure follows the current frame,
// so every frame of a static scene is the same (deterministic goldens). Declared after bloom
// (which reads this frame's pre-exposure) and before tone mapping.
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class ExposureFeature final : public IRenderFeature {
 public:
  static constexpr float kKey = 0.18f;  // middle grey

  [[nodiscard]] std::string_view name() const override { return "exposure"; }
  [[nodiscard]] bool enabled() const override { return enabled_; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

 private:
  bool enabled_ = false;
  rhi::PipelineId reducePipeline_;
  rhi::PipelineId updatePipeline_;
  uint32_t stateIndex_ = 0;
};

}  // namespace fgb::features
