// "Tone mapping": L = 1 - exp(-L_hdr * exposure) (thesis), adding the bloom texture when the bloom
// feature published one, into the sRGB display image. The HDR image is pre-exposed; the shader
// applies the exposure state's tonemapScale (ExposureGpu).
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
  uint32_t exposureBuffer_ = 0;
  float bloomIntensity_ = 0.0f;
};

}  // namespace fgb::features
