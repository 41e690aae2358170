// "Tone mapping": L = 1 - exp(-L_hdr * exposure) (thesis), adding the bloom texture when the bloom
// feature published one, into the display image. The HDR image is pre-exposed; the shader applies
// the exposure state's tonemapScale (gpu::Exposure). Fragment form (tonemap.frag): a full-screen
// pass into the sRGB display target. Compute form (tonemap.comp, the visibility-buffer path): the
// display image is R8G8B8A8_UNORM with storage usage and receives the same sRGB-encoded bytes
// (storage images cannot be sRGB on most devices). The maths is shared (include/tonemap.glsl).
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class TonemapFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "tonemap"; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

  // The display image's format for each form (the workload creates the image).
  [[nodiscard]] static graph::Format displayFormat(PostPassForm form);

 private:
  PostPassForm form_ = PostPassForm::Fragment;  // the path's "post"
  rhi::PipelineId pipeline_;
  uint32_t samplerIndex_ = 0;
  uint32_t exposureBuffer_ = 0;
  float bloomIntensity_ = 0.0f;
  bool injectBias_ = false;  // debug.inject_bias=Tone mapping
};

}  // namespace fgb::features
