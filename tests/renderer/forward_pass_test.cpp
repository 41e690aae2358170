// addForwardPass: the first colour pass clears, later ones load, and only the last one resolves
// the multisampled target into the imported HDR image.
#include "features/context/render_feature.hpp"

#include <gtest/gtest.h>

namespace fgb::features {
namespace {

FrameTargets makeTargets(graph::FrameGraph& graph, uint32_t samples, uint32_t passes) {
  FrameTargets targets;
  targets.samples = samples;
  targets.extent = {64, 32, 1};
  const graph::ImportState state{};
  targets.hdr = graph.importTexture("hdr", {kHdrFormat, targets.extent, 1, 1, 1, {}, 0}, {1}, state, state);
  targets.color = samples == 1 ? targets.hdr
                               : graph.createTexture("msaa", {kHdrFormat, {}, 1, 1, samples, targets.hdr, 0});
  targets.depth = graph.createTexture("depth", {kDepthFormat, {}, 1, 1, samples, targets.hdr, 0});
  targets.colorPasses = passes;
  return targets;
}

TEST(ForwardPass, OnlyTheLastPassResolves) {
  graph::FrameGraph graph;
  auto targets = makeTargets(graph, 4, 2);
  const auto hdrBefore = targets.hdr;
  addForwardPass(graph, targets, "first", true);
  EXPECT_EQ(targets.hdr, hdrBefore);
  addForwardPass(graph, targets, "second", false);
  EXPECT_NE(targets.hdr, hdrBefore);
  ASSERT_EQ(graph.nodes().size(), 2u);
  EXPECT_EQ(graph.attachments(0).color.at(0).load, graph::LoadOp::Clear);
  EXPECT_FALSE(graph.attachments(0).color.at(0).resolveTarget.valid());
  EXPECT_EQ(graph.attachments(1).color.at(0).load, graph::LoadOp::Load);
  EXPECT_TRUE(graph.attachments(1).color.at(0).resolveTarget.valid());
  EXPECT_TRUE(graph.attachments(1).depth.readOnly);
  EXPECT_THROW(addForwardPass(graph, targets, "unannounced", true), std::logic_error);
}

TEST(ForwardPass, SingleSampleWritesTheHdrImageDirectly) {
  graph::FrameGraph graph;
  auto targets = makeTargets(graph, 1, 1);
  addForwardPass(graph, targets, "only", true);
  EXPECT_EQ(targets.hdr, targets.color);
  EXPECT_EQ(graph.resourceOf(targets.hdr), 0u);  // the imported image
  EXPECT_FALSE(graph.attachments(0).color.at(0).resolveTarget.valid());
}

}  // namespace
}  // namespace fgb::features
