// Stress ladders: parsing (built-in and custom), verdicts against the baseline's noise, summary.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fgb/core/error.hpp>
#include <fgb/harness/stress/stress.hpp>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::string& text) {
  try {
    parseLadder(text, {});
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(StressLadder, BuiltinOffsetMovesTheSceneWithItsIssueThreshold) {
  const StressLadder ladder = parseLadder("offset=0,1e3,1e7", {});
  EXPECT_EQ(ladder.name, "offset");
  ASSERT_EQ(ladder.rungs.size(), 3u);
  EXPECT_EQ(ladder.rungs[2].knobs.at("scene.offset"), "1e7");
  EXPECT_DOUBLE_EQ(ladder.rungs[2].axis, 1e7);
  EXPECT_TRUE(ladder.compareImages);
  EXPECT_DOUBLE_EQ(ladder.thresholds.flipMean, 0.005);
  EXPECT_EQ(parseLadder("offset", {}).rungs.size(), 5u);  // default rungs 0 ... 1e7
}

TEST(StressLadder, NearRunsWithFarFiniteThenInfinite) {
  const StressLadder ladder = parseLadder("near=1e-1,1e-4", {});
  ASSERT_EQ(ladder.rungs.size(), 4u);
  EXPECT_EQ(ladder.rungs[0].knobs,
            (std::map<std::string, std::string>{{"camera.near", "1e-1"}, {"camera.far", "1e5"}}));
  EXPECT_EQ(ladder.rungs[3].value, "1e-4 far=inf");
  EXPECT_EQ(ladder.rungs[3].knobs.at("camera.far"), "inf");
  EXPECT_DOUBLE_EQ(ladder.thresholds.flipMean, 0.002);
}

TEST(StressLadder, LightScaleCompensatesTheExposure) {
  const StressLadder ladder = parseLadder("light-scale=1,1e6", {0.5, false});
  EXPECT_EQ(ladder.rungs[1].knobs.at("scene.light_scale"), "1e6");
  EXPECT_EQ(ladder.rungs[1].knobs.at("post.exposure"), "5e-07");
  const StressLadder automatic = parseLadder("light-scale=1,1e6", {0.5, true});
  EXPECT_FALSE(automatic.rungs[1].knobs.count("post.exposure"));
}

TEST(StressLadder, FovRadianceAndResolutionJudgeOnlyFiniteness) {
  EXPECT_FALSE(parseLadder("fov", {}).compareImages);
  EXPECT_FALSE(parseLadder("radiance=1,1e8", {}).compareImages);
  const StressLadder sizes = parseLadder("resolution=320x180,1x1", {});
  EXPECT_FALSE(sizes.compareImages);
  EXPECT_EQ(sizes.rungs[1].width, 1u);
  EXPECT_EQ(sizes.rungs[1].height, 1u);
}

TEST(StressLadder, CustomKnobLadder) {
  const StressLadder ladder = parseLadder("lighting.max_per_cluster=128,4", {});
  EXPECT_EQ(ladder.name, "lighting.max_per_cluster");
  EXPECT_TRUE(ladder.compareImages);
  EXPECT_EQ(ladder.rungs[1].knobs.at("lighting.max_per_cluster"), "4");
}

TEST(StressLadder, BadLaddersNameTheOption) {
  EXPECT_EQ(errorOf("offset=0"), "--ladder offset=0: expected a baseline and at least one more rung (V0,V1,...)");
  EXPECT_EQ(errorOf("offset=0,,1"), "--ladder offset=0,,1: empty value");
  EXPECT_EQ(errorOf("offset=0,1,1"), "--ladder offset=0,1,1: value '1' repeated");
  EXPECT_EQ(errorOf("offset=0,far"), "--ladder offset=0,far: 'far' is not a number");
  EXPECT_EQ(errorOf("resolution=1x1,big"), "--ladder resolution=1x1,big: 'big' is not a size WxH");
  EXPECT_THAT(errorOf("wobble"), HasSubstr("unknown ladder (built-in: offset, near, light-scale, radiance, fov"));
  EXPECT_EQ(errorOf("near=0,1"), "--ladder near=0,1: near plane '0' must be > 0");
}

ImageMetrics metrics(double flip, double share, double maxAbs = 0.0) {
  ImageMetrics m;
  m.flip = FlipStatistics{};
  m.flip->mean = flip;
  m.shareOverThreshold = share;
  m.maxAbsError = maxAbs;
  return m;
}

StressRungOutcome rung(std::string value, std::optional<ImageMetrics> display) {
  StressRungOutcome r;
  r.rung.axis = std::stod(value);
  r.rung.value = std::move(value);
  r.rendered = true;
  r.display = std::move(display);
  return r;
}

TEST(StressVerdict, FlipIsJudgedAboveTheBaselineNoise) {
  StressLadder ladder = parseLadder("offset=0,1", {});
  const ImageMetrics noise = metrics(0.001, 0.0);
  StressRungOutcome close = rung("1", metrics(0.0055, 0.0));  // 0.0045 above the noise: within 0.005
  judgeRung(close, ladder, noise);
  EXPECT_TRUE(close.pass) << close.failure;
  StressRungOutcome far = rung("1", metrics(0.0070, 0.0));
  judgeRung(far, ladder, noise);
  EXPECT_FALSE(far.pass);
  EXPECT_EQ(far.failure, "FLIP mean = 0.007 > 0.005 + noise 0.001");
  StressRungOutcome spread = rung("1", metrics(0.0, 0.2));
  judgeRung(spread, ladder, noise);
  EXPECT_THAT(spread.failure, HasSubstr("pixels over 2/255 = 20.00% > 5.00%"));
  ladder.thresholds.maxAbs = 0.1;
  StressRungOutcome jump = rung("1", metrics(0.0, 0.0, 0.5));
  judgeRung(jump, ladder, noise);
  EXPECT_EQ(jump.failure, "max abs error = 0.5 > 0.1");
}

TEST(StressVerdict, NonFiniteValuesFailEvenWhereImagesAreNotCompared) {
  const StressLadder ladder = parseLadder("radiance=1,1e8", {});
  StressRungOutcome bright = rung("1e8", std::nullopt);
  bright.nonFinite = {{"Mesh Render", 0, 0, 0}, {"Bloom", 0, 12, 3}};
  judgeRung(bright, ladder, {});
  EXPECT_FALSE(bright.pass);
  EXPECT_EQ(bright.failure, "non-finite values in Bloom (NaN 0, Inf 12, > 32752 3)");
  StressRungOutcome failed = rung("1e8", std::nullopt);
  failed.rendered = false;
  failed.error = "out of device memory";
  judgeRung(failed, ladder, {});
  EXPECT_EQ(failed.failure, "did not render: out of device memory");
  // Above half of R16F's maximum: reported, failing only when asked.
  StressLadder strict = ladder;
  StressRungOutcome large = rung("1e4", std::nullopt);
  large.nonFinite = {{"Particle Render", 0, 0, 1}};
  judgeRung(large, ladder, {});
  EXPECT_TRUE(large.pass);
  strict.thresholds.overHalfMax = true;
  judgeRung(large, strict, {});
  EXPECT_EQ(large.failure, "non-finite values in Particle Render (NaN 0, Inf 0, > 32752 1)");
}

TEST(StressResult, SummarySaysWhereItStoppedBeingStable) {
  StressResult result;
  result.ladder = parseLadder("offset=0,1e6,1e7", {});
  result.rungs = {rung("0", std::nullopt), rung("1e6", metrics(0, 0)), rung("1e7", metrics(0.4, 0))};
  for (auto& r : result.rungs) judgeRung(r, result.ladder, {});
  EXPECT_EQ(result.summary(), "stable up to 1e6; first failure at 1e7: FLIP mean = 0.4 > 0.005 + noise 0");
  EXPECT_EQ(result.firstFailure(), std::optional<std::size_t>(2));
  const auto json = toJson(result);
  EXPECT_EQ(json["verdict"], "fail");
  EXPECT_EQ(json["first_failure"], "1e7");
  EXPECT_THAT(stressMarkdown(result), HasSubstr("| 1e7 | 0.40000 |"));
  EXPECT_THAT(stressHtml(result), HasSubstr("<svg"));
  result.rungs.pop_back();
  EXPECT_EQ(result.summary(), "stable through 1e6");
}

}  // namespace
}  // namespace fgb::harness
