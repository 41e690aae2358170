// "Tone mapping": L = 1 - exp(-L_hdr * exposure) (thesis), adding the bloom texture when the bloom
// feature published one, into the sRGB display image.
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class TonemapFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "tonemap"; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

 private:
  rhi::PipelineId pipeline_;
  uint32_t samplerIndex_ = 0;
  float exposure_ = 0.6f;
  float bloomIntensity_ = 0.0f;
};

}  // namespace fgb::features
