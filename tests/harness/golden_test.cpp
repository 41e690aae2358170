#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/results/golden.hpp>

#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;

TEST(Golden, NamesForScenesAndDevices) {
  EXPECT_EQ(sceneName("builtin:proof"), "proof");
  EXPECT_EQ(sceneName("scenes/atrium.json"), "atrium");
  render::DeviceDescription gpu;
  gpu.type = "discrete";
  gpu.name = "NVIDIA GeForce GTX 1660 Ti (Max-Q)";
  EXPECT_EQ(deviceClass(gpu), "nvidia-geforce-gtx-1660-ti-max-q");
  render::DeviceDescription cpu;
  cpu.type = "cpu";
  cpu.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
  EXPECT_EQ(deviceClass(cpu), "lavapipe");
}

TEST(Golden, MissingGoldenIsInputErrorPointingAtBless) {
  testing::ScratchDir dir;
  try {
    loadGolden(dir.path());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("default.json"));
    EXPECT_THAT(e.what(), HasSubstr("bless"));
  }
}

TEST(Golden, LoadsThresholdsConfigAndImages) {
  testing::ScratchDir dir;
  Image img = makeImage(4, 4, Encoding::Linear);
  writePng(dir / "default.png", img);
  const nlohmann::json doc{{"schema", 1},
                           {"images", {{"display", "default.png"}}},
                           {"config", {{"width", 4}, {"height", 4}, {"msaa", 4}, {"knobs", {{"bloom", "off"}}}}},
                           {"thresholds", {{"display", {{"flip_mean", 0.01}, {"rmse", 0.02}}}}}};
  writeFileAtomic(dir / "default.json", dumpJson(doc));
  const Golden g = loadGolden(dir.path());
  EXPECT_EQ(g.config.msaa, 4u);
  EXPECT_EQ(g.config.knobs.at("bloom"), "off");
  ASSERT_TRUE(g.display.flipMean);
  EXPECT_DOUBLE_EQ(*g.display.flipMean, 0.01);
  EXPECT_FALSE(g.display.maxAbsError);
  EXPECT_TRUE(g.hdrImage.empty());
}

TEST(Golden, MissingImageOrBadThresholdIsInputError) {
  testing::ScratchDir dir;
  writeFileAtomic(dir / "a.json", dumpJson({{"images", {{"display", "gone.png"}}}, {"thresholds", {{"display", nlohmann::json::object()}}}}));
  EXPECT_THROW(loadGolden(dir / "a.json"), InputError);
  writePng(dir / "x.png", makeImage(2, 2, Encoding::Linear));
  writeFileAtomic(dir / "b.json", dumpJson({{"images", {{"display", "x.png"}}}, {"thresholds", {{"display", {{"rmse", -1}}}}}}));
  EXPECT_THROW(loadGolden(dir / "b.json"), InputError);
}

TEST(Golden, JudgeFailsOverThresholdsAndAlwaysOnNaN) {
  ImageMetrics m;
  m.rmse = 0.05;
  m.flip = FlipStatistics{"ldr", 0.02, 0.0, 0.0, 0.1, 0.2, 0, 0, 0};
  Thresholds limits;
  limits.rmse = 0.1;
  limits.flipMean = 0.01;
  ImageVerdict v = judgeImage("display", m, limits);
  ASSERT_EQ(v.failures.size(), 1u);
  EXPECT_THAT(v.failures[0], HasSubstr("flip_mean"));

  limits.flipMean = 0.5;
  EXPECT_TRUE(judgeImage("display", m, limits).failures.empty());
  m.nonFiniteTest = 3;
  v = judgeImage("display", m, Thresholds{});  // no limits at all: NaN still fails
  ASSERT_EQ(v.failures.size(), 1u);
  EXPECT_THAT(v.failures[0], HasSubstr("NaN"));
}

TEST(Golden, ThresholdsFromNoiseStayAboveNoiseAndFloors) {
  ImageMetrics noise;
  noise.rmse = 0.02;
  noise.flip = FlipStatistics{"ldr", 0.01, 0, 0, 0.3, 0.5, 0, 0, 0};
  const Thresholds t = thresholdsFromNoise(noise, false);
  EXPECT_DOUBLE_EQ(*t.rmse, 0.06);
  EXPECT_DOUBLE_EQ(*t.flipMean, 0.03);
  EXPECT_NEAR(*t.flipP99, 0.9, 1e-12);
  const Thresholds quiet = thresholdsFromNoise(std::nullopt, false);
  EXPECT_GT(*quiet.flipMean, 0.0);
  EXPECT_GT(*quiet.rmse, 0.0);
}

}  // namespace
}  // namespace fgb::harness
