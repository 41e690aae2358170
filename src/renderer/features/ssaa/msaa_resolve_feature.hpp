// "MSAA Resolve": the scene's colour passes (addForwardPass) draw into FrameTargets::color,
// multisampled when samples > 1, and resolve nothing themselves. The render path composes this
// feature after the last feature that draws colour; it declares the resolve as a graph node that
// writes the single-sample HDR image (a render pass that loads the samples, draws nothing and
// resolves into its resolve attachment at its end), so the Graphviz dump shows where it happens.
// Afterwards FrameTargets::colorResolved is set: addForwardPass throws for any later colour pass
// (it would draw into samples nobody resolves) and "SSAA Resolve" checks it ran.
//
// Single-sampled, the colour passes wrote the HDR image itself and no resolve node is declared.
// If nothing drew colour at all (an empty scene), a "Clear" pass first gives the HDR image the
// background, so bloom and tone mapping read a defined image.
#pragma once

#include "../context/render_feature.hpp"

namespace fgb::features {

class MsaaResolveFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "msaa resolve"; }
  void initialize(FeatureInit& /*init*/) override {}
  void declare(graph::FrameGraph& graph, Blackboard& board) override;
};

}  // namespace fgb::features
