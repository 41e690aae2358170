// "SSAA Resolve" (render.ssaa = S > 1): the scene passes (meshes, lights, particles) render at
// S*W x S*H into a supersampled HDR image, MSAA-resolved there as usual; this node filters it down
// to the W x H HDR image that bloom and tone mapping read, so post effects run at output size.
//
// Filter: a box over each output pixel's S x S block of scene pixels (equal weights, 1/S^2), i.e.
// the mean of the S*S scene pixels whose centres lie inside the output pixel. With MSAA M on top,
// each scene pixel is already the mean of its M samples, so the output is the equal-weight mean of
// S*S*M samples. Deterministic (fixed summation order), and exact for constant regions.
//
// Fragment form (ssaa_resolve.frag): a full-screen pass. Compute form (ssaa_resolve.comp, the
// visibility-buffer path, whose output HDR image has storage usage): one invocation per output
// pixel. The filter is shared (include/ssaa.glsl), so both write the same values.
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class SsaaResolveFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "ssaa resolve"; }
  [[nodiscard]] bool enabled() const override { return factor_ > 1; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

 private:
  PostPassForm form_ = PostPassForm::Fragment;  // the path's "post"
  rhi::PipelineId pipeline_;
  uint32_t factor_ = 1;
};

}  // namespace fgb::features
