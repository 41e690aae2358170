// Per-pass captures and first-difference localisation (pass_capture.hpp, pass_golden.hpp): the
// files round-trip exactly, and the verdict names the node where a difference enters, through
// nodes without captures and across parallel branches.
#include <gtest/gtest.h>

#include <fgb/core/error.hpp>
#include <fgb/harness/passes/pass_golden.hpp>

#include "test_util.hpp"

namespace fgb::harness {
namespace {

using render::CaptureContent;

render::PassCapture capture(const std::string& pass, const std::string& resource, CaptureContent content, float value) {
  render::PassCapture c{pass, resource, content, {4, 2, std::vector<float>(4 * 2 * 4, value)}};
  return c;
}

// A -> B -> C, and D (parallel, reading A) -> E (reading C and D); "Cull" writes only counts and
// feeds B; "Hidden" has nothing captured and sits between C and E.
std::vector<render::PassNode> graph() {
  return {{"A", {}}, {"Cull", {}}, {"B", {0, 1}}, {"C", {2}}, {"Hidden", {3}}, {"D", {0}}, {"E", {4, 5}}};
}

PassCaptureSet set(float b, float d, double visible) {
  std::vector<render::PassCapture> captures{
      capture("A", "hdr", CaptureContent::Color, 0.5f),    capture("B", "hdr", CaptureContent::Color, b),
      capture("B", "depth", CaptureContent::Depth, 0.25f), capture("C", "hdr", CaptureContent::Color, b * 2.0f),
      capture("D", "hdr", CaptureContent::Color, d),       capture("E", "display", CaptureContent::Color, b + d)};
  // "instances_visible" belongs to "Mesh Frustum Cull": rename the node so the count attaches.
  auto nodes = graph();
  nodes[1].name = "Mesh Frustum Cull";
  return makeCaptureSet(captures, nodes, {{"instances_visible", visible}, {"unrelated", 3.0}});
}

LoadedCaptureSet roundTrip(const PassCaptureSet& golden, const testing::ScratchDir& dir) {
  writeCaptureSet(dir.path() / "passes", golden, passGoldenExtras({golden, golden}));
  return readCaptureSet(dir.path() / "passes");
}

TEST(PassGolden, FilesNameEachImageAndRoundTripExactly) {
  testing::ScratchDir dir;
  const PassCaptureSet golden = set(0.125f, 0.75f, 81);
  ASSERT_EQ(golden.images.size(), 6u);
  EXPECT_EQ(golden.images[0].file, "A.exr");      // one image: the node's name
  EXPECT_EQ(golden.images[1].file, "B-hdr.exr");  // several: with the resource
  EXPECT_EQ(golden.images[2].file, "B-depth.exr");
  ASSERT_EQ(golden.stats.size(), 1u);  // only counts the table attributes to a node of this frame
  EXPECT_EQ(golden.stats[0].pass, "Mesh Frustum Cull");
  const LoadedCaptureSet loaded = roundTrip(golden, dir);
  const PassLocalisation same = localise(loaded, golden);
  EXPECT_TRUE(same.firstDifferences.empty());
  EXPECT_TRUE(same.differing.empty());
  EXPECT_EQ(same.line, "no captured pass differs from its golden");
}

TEST(PassGolden, NamesTheNodeWhereTheDifferenceEntersAndTheMatchingOnesBefore) {
  testing::ScratchDir dir;
  const LoadedCaptureSet golden = roundTrip(set(0.125f, 0.75f, 81), dir);
  const PassLocalisation l = localise(golden, set(0.25f, 0.75f, 81));  // B (and so C, E) changed
  EXPECT_EQ(l.differing, (std::vector<std::string>{"B", "C", "E"}));
  EXPECT_EQ(l.firstDifferences, (std::vector<std::string>{"B"}));
  EXPECT_EQ(l.matchingBefore, (std::vector<std::string>{"A", "Mesh Frustum Cull"}));
  EXPECT_EQ(l.line.rfind("first difference at \"B\" (FLIP ", 0), 0u) << l.line;
  EXPECT_NE(l.line.find("100.0% of pixels); \"A\", \"Mesh Frustum Cull\" identical"), std::string::npos) << l.line;
}

TEST(PassGolden, ParallelBranchesAreEachNamed) {
  testing::ScratchDir dir;
  const LoadedCaptureSet golden = roundTrip(set(0.125f, 0.75f, 81), dir);
  const PassLocalisation l = localise(golden, set(0.25f, 0.5f, 81));  // B and D both changed
  EXPECT_EQ(l.firstDifferences, (std::vector<std::string>{"B", "D"}));
  EXPECT_EQ(l.line.rfind("first differences at \"B\"", 0), 0u) << l.line;
}

TEST(PassGolden, AChangedCountNamesItsNode) {
  testing::ScratchDir dir;
  const LoadedCaptureSet golden = roundTrip(set(0.125f, 0.75f, 81), dir);
  const PassLocalisation l = localise(golden, set(0.25f, 0.75f, 80));  // the cull lost an instance
  EXPECT_EQ(l.firstDifferences, (std::vector<std::string>{"Mesh Frustum Cull"}));
  EXPECT_EQ(l.line,
            "first difference at \"Mesh Frustum Cull\" (visible instances 81 → 80); no captured pass before it");
}

TEST(PassGolden, NoiseBetweenRendersBecomesEachImagesAllowance) {
  const PassCaptureSet a = set(0.125f, 0.75f, 81);
  PassCaptureSet b = a;
  b.images[4].image.rgba[0] += 0.5f;  // one of D's 8 pixels moved between identical renders
  b.stats[0].value = 83;
  const CaptureExtras extras = passGoldenExtras({a, b});
  EXPECT_DOUBLE_EQ(extras.images.at("D.exr")["noise"]["share"].get<double>(), 1.0 / 8.0);
  EXPECT_DOUBLE_EQ(extras.images.at("D.exr")["thresholds"]["share"].get<double>(), 3.0 / 8.0);
  EXPECT_DOUBLE_EQ(extras.images.at("A.exr")["thresholds"]["share"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(extras.statTolerances.at("instances_visible"), 2.0);
}

TEST(PassGolden, CaptureListsAreCheckedAndSplit) {
  EXPECT_TRUE(parseCaptureList("passes").empty());
  EXPECT_EQ(parseCaptureList("Mesh Render, Bloom"), (std::vector<std::string>{"Mesh Render", "Bloom"}));
  EXPECT_THROW(parseCaptureList("Bloom,,Tone mapping"), InputError);
}

}  // namespace
}  // namespace fgb::harness
