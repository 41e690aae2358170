// addForwardPass and "MSAA Resolve": the first colour pass clears, later ones load, none resolves;
// MsaaResolveFeature, composed after the last colour pass, declares the resolve into the HDR image
// as its own node, and any colour pass declared after it is refused.
#include "features/context/render_feature.hpp"
#include "features/ssaa/msaa_resolve_feature.hpp"

#include <gtest/gtest.h>

namespace fgb::features {
namespace {

FrameTargets makeTargets(graph::FrameGraph& graph, uint32_t samples) {
  FrameTargets targets;
  targets.samples = samples;
  targets.extent = {64, 32, 1};
  const graph::ImportState state{};
  targets.hdr = graph.importTexture("hdr", {kHdrFormat, targets.extent, 1, 1, 1, {}, 0}, {1}, state, state);
  targets.color =
      samples == 1 ? targets.hdr : graph.createTexture("msaa", {kHdrFormat, {}, 1, 1, samples, targets.hdr, 0});
  targets.depth = graph.createTexture("depth", {kDepthFormat, {}, 1, 1, samples, targets.hdr, 0});
  return targets;
}

void declareResolve(graph::FrameGraph& graph, Blackboard& board) {
  MsaaResolveFeature resolve;
  resolve.declare(graph, board);
}

TEST(ForwardPass, TheMsaaResolveIsItsOwnNodeAfterTheColourPasses) {
  graph::FrameGraph graph;
  Blackboard board;
  auto& targets = board.set(makeTargets(graph, 4));
  const auto hdrBefore = targets.hdr;
  addForwardPass(graph, targets, "first", true);
  addForwardPass(graph, targets, "second", false);
  EXPECT_EQ(targets.hdr, hdrBefore);
  const auto samplesDrawn = targets.color;
  declareResolve(graph, board);

  ASSERT_EQ(graph.nodes().size(), 3u);
  EXPECT_EQ(graph.attachments(0).color.at(0).load, graph::LoadOp::Clear);
  EXPECT_EQ(graph.attachments(1).color.at(0).load, graph::LoadOp::Load);
  EXPECT_TRUE(graph.attachments(1).depth.readOnly);
  for (uint32_t pass = 0; pass < 2; ++pass) EXPECT_FALSE(graph.attachments(pass).color.at(0).resolveTarget.valid());

  EXPECT_EQ(graph.nodes()[2].name, "MSAA Resolve");
  const auto& resolve = graph.attachments(2).color.at(0);
  EXPECT_EQ(resolve.load, graph::LoadOp::Load);
  EXPECT_EQ(graph.resourceOf(resolve.target), graph.resourceOf(samplesDrawn));  // the multisampled target
  EXPECT_EQ(resolve.target, targets.color);
  EXPECT_EQ(resolve.resolveTarget, targets.hdr);
  EXPECT_NE(targets.hdr, hdrBefore);
  EXPECT_EQ(graph.resourceOf(targets.hdr), graph.resourceOf(hdrBefore));  // the single-sample image
  EXPECT_TRUE(targets.colorResolved);

  EXPECT_THROW(addForwardPass(graph, targets, "after the resolve", false), std::logic_error);
  EXPECT_THROW(declareResolve(graph, board), std::logic_error);
}

TEST(ForwardPass, SingleSampleWritesTheHdrImageDirectlyAndNeedsNoResolveNode) {
  graph::FrameGraph graph;
  Blackboard board;
  auto& targets = board.set(makeTargets(graph, 1));
  addForwardPass(graph, targets, "only", true);
  EXPECT_EQ(targets.hdr, targets.color);
  EXPECT_EQ(graph.resourceOf(targets.hdr), 0u);  // the imported image
  EXPECT_FALSE(graph.attachments(0).color.at(0).resolveTarget.valid());
  declareResolve(graph, board);
  EXPECT_EQ(graph.nodes().size(), 1u);
  EXPECT_TRUE(targets.colorResolved);
  EXPECT_THROW(addForwardPass(graph, targets, "after the resolve", false), std::logic_error);
}

TEST(ForwardPass, NothingDrawnGetsAClearPassBeforeTheResolve) {
  for (const uint32_t samples : {1u, 4u}) {
    graph::FrameGraph graph;
    Blackboard board;
    auto& targets = board.set(makeTargets(graph, samples));
    const auto hdrBefore = targets.hdr;
    declareResolve(graph, board);
    ASSERT_EQ(graph.nodes().size(), samples == 1 ? 1u : 2u) << samples;
    EXPECT_EQ(graph.nodes()[0].name, "Clear");
    EXPECT_EQ(graph.attachments(0).color.at(0).load, graph::LoadOp::Clear);
    EXPECT_NE(targets.hdr, hdrBefore) << samples;  // the HDR image was written
  }
}

}  // namespace
}  // namespace fgb::features
