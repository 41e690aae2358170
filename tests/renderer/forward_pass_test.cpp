// addForwardPass and "MSAA Resolve": the first colour pass clears, later ones load, none resolves;
// MsaaResolveFeature, composed after the last colour pass, declares the resolve into the HDR image
// as its own node, and any colour pass declared after it is refused.
#include <gtest/gtest.h>

#include <algorithm>

#include "features/context/render_feature.hpp"
#include "features/ssaa/msaa_resolve_feature.hpp"

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

// The visibility-buffer path's colour passes after the opaque scene: no depth attachment; each
// reads the opaque depth buffer (its fragment shader tests against it) and cannot write depth.
TEST(ForwardPass, TheOpaqueDepthBufferFormReadsTheBufferInsteadOfADepthAttachment) {
  graph::FrameGraph graph;
  Blackboard board;
  auto& targets = board.set(makeTargets(graph, 1));
  targets.colorCleared = true;  // "Material Shade" wrote the colour and the opaque depth
  const auto depthBefore = targets.depth;
  auto shade = graph.addNode("shade", graph::NodeType::Compute);
  targets.opaqueDepth =
      shade.write(graph.createBuffer("visibility depth", {uint64_t{4} * 64 * 32, {}}), graph::Access::StorageWrite);
  addForwardPass(graph, targets, "transparent", false, DepthTest::OpaqueDepthBuffer);
  addForwardPass(graph, targets, "particles", false, DepthTest::OpaqueDepthBuffer);

  for (uint32_t pass = 1; pass < 3; ++pass) {
    EXPECT_FALSE(graph.attachments(pass).depth.target.valid()) << pass;
    EXPECT_EQ(graph.attachments(pass).color.at(0).load, graph::LoadOp::Load) << pass;
    const auto accesses = graph.accesses(pass);
    const bool readsDepth = std::any_of(accesses.begin(), accesses.end(), [&](const graph::ResourceAccess& a) {
      return a.access == graph::Access::StorageRead && a.readVersion == targets.opaqueDepth.version;
    });
    EXPECT_TRUE(readsDepth) << pass;
  }
  EXPECT_EQ(targets.depth, depthBefore);  // the depth image is not used
  EXPECT_FALSE(targets.depthCleared);
  const OpaqueDepthSource source = opaqueDepthSource(targets, DepthTest::OpaqueDepthBuffer);
  EXPECT_EQ(source.buffer, targets.opaqueDepth);
  EXPECT_EQ(source.rowStride, 64u);
  EXPECT_FALSE(opaqueDepthSource(targets, DepthTest::Attachment).buffer.valid());
  EXPECT_THROW(addForwardPass(graph, targets, "writes depth", true, DepthTest::OpaqueDepthBuffer), std::logic_error);
}

// Nothing opaque drawn (no buffer): the pass still has no attachment (its pipeline has no depth
// format) and its shader's test passes everything (OpaqueDepthSource without a buffer).
TEST(ForwardPass, TheOpaqueDepthBufferFormWithoutOpaqueGeometryReadsNothing) {
  graph::FrameGraph graph;
  Blackboard board;
  auto& targets = board.set(makeTargets(graph, 1));
  addForwardPass(graph, targets, "transparent", false, DepthTest::OpaqueDepthBuffer);
  EXPECT_FALSE(graph.attachments(0).depth.target.valid());
  EXPECT_EQ(graph.attachments(0).color.at(0).load, graph::LoadOp::Clear);
  EXPECT_TRUE(graph.accesses(0).size() == 1);  // the colour target only
  EXPECT_FALSE(opaqueDepthSource(targets, DepthTest::OpaqueDepthBuffer).buffer.valid());
}

TEST(ForwardPass, DepthStateFollowsTheForm) {
  rhi::GraphicsPipelineDesc attachment;
  setDepthState(attachment, DepthTest::Attachment, false);
  EXPECT_EQ(attachment.depthFormat, kDepthFormat);
  EXPECT_TRUE(attachment.depthTest);
  EXPECT_FALSE(attachment.depthWrite);
  EXPECT_EQ(attachment.depthCompare, kDepthCompare);
  rhi::GraphicsPipelineDesc buffer = attachment;
  setDepthState(buffer, DepthTest::OpaqueDepthBuffer, false);
  EXPECT_EQ(buffer.depthFormat, graph::Format::Undefined);
  EXPECT_FALSE(buffer.depthTest);
  EXPECT_THROW(setDepthState(buffer, DepthTest::OpaqueDepthBuffer, true), std::logic_error);
}

// opaque_depth.glsl reads the compare op pushed as its value as a pass mask: bit 0 passes a
// fragment nearer in "less", bit 1 an equal depth, bit 2 a greater one (as VkCompareOp is laid out).
TEST(ForwardPass, CompareOpValuesArePassMasksAsTheShaderReadsThem) {
  using rhi::CompareOp;
  const auto mask = [](CompareOp op) { return static_cast<uint32_t>(op); };
  EXPECT_EQ(mask(CompareOp::Never), 0u);
  EXPECT_EQ(mask(CompareOp::Less), 1u);
  EXPECT_EQ(mask(CompareOp::Equal), 2u);
  EXPECT_EQ(mask(CompareOp::Greater), 4u);
  EXPECT_EQ(mask(CompareOp::LessOrEqual), 1u | 2u);
  EXPECT_EQ(mask(CompareOp::GreaterOrEqual), 2u | 4u);
  EXPECT_EQ(mask(CompareOp::NotEqual), 1u | 4u);
  EXPECT_EQ(mask(CompareOp::Always), 7u);
}

}  // namespace
}  // namespace fgb::features
