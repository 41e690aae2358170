// Bloom (Jimenez 2014): "Bloom Downsample k" builds a chain of half-size HDR textures with the
// 13-tap filter (Karis-weighted and soft-thresholded on the first), "Bloom Upsample k" adds the
// 3x3-tent-filtered smaller level onto the larger one, and tone mapping composes level 1 into the
// image (BloomOutput). The thesis' single "Bloom" budget is the sum of the "Bloom *" nodes.
// Parameters: post.bloom, post.bloom_threshold, post.bloom_knee, post.bloom_intensity,
// post.bloom_radius (scene knobs) and bloom.mips.
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class BloomFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "bloom"; }
  [[nodiscard]] bool enabled() const override { return enabled_; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

 private:
  rhi::PipelineId downPipeline_;
  rhi::PipelineId upPipeline_;
  uint32_t samplerIndex_ = 0;
  uint32_t mips_ = 0;
  scene::BloomSettings bloom_;
  bool enabled_ = false;
};

}  // namespace fgb::features
