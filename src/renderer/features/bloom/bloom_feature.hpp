// Bloom (Jimenez 2014) as one compute node, "Bloom" (the thesis' single budget row): it builds a
// chain of half-size HDR textures with the 13-tap filter (Karis-weighted and soft-thresholded on
// the first level), then adds each 3x3-tent-filtered smaller level onto the next larger one; one
// dispatch per level, with a barrier inside the node between them. Tone mapping composes level 1
// into the image (BloomOutput). The node runs on the graphics queue: the HDR image and level 1
// stay with the passes around it (no ownership transfers of full-size images).
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
  uint32_t exposureIndex_ = 0;  // the exposure state (the threshold is applied pre-exposed)
  uint32_t mips_ = 0;
  scene::BloomSettings bloom_;
  bool enabled_ = false;
  bool injectNan_ = false;   // debug.inject_nan=Bloom
  bool injectBias_ = false;  // debug.inject_bias=Bloom
};

}  // namespace fgb::features
