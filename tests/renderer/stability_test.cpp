// The renderer's numerical stability (issue 17): camera-relative rendering far from the origin,
// reversed-Z with a tiny near plane and an infinite far one, pre-exposure under extreme light
// scales, auto exposure, and NaN-safe shading. Each test compares against a plain render of the
// same scene, or checks a property the old renderer failed (noted per test).
#include <fgb/renderer/scene_workload.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "scene_render.hpp"

namespace fgb::render {
namespace {

using scene_test::kRepositoryScenes;
using scene_test::kScenes;
using scene_test::meanOf;

struct Frame {
  ImageRGBA32F display;
  ImageRGBA32F hdr;
  std::vector<PassTiming> passes;
  uint64_t validationMessages = 0;
};

Frame render(const std::string& scene, std::map<std::string, std::string> knobs, uint32_t frames = 3,
             uint32_t width = 160, uint32_t height = 90) {
  WorkloadConfig config;
  config.scenePath = scene;
  config.device = "lavapipe";
  config.validation = true;
  config.width = width;
  config.height = height;
  config.msaa = 1;
  config.knobs = std::move(knobs);
  auto workload = openSceneWorkload(config);
  for (uint32_t i = 0; i < frames; ++i) workload->renderFrame();
  const auto rest = workload->finish();
  Frame frame{workload->readDisplay(), workload->readHdr(),
              rest.empty() ? std::vector<PassTiming>{} : rest.back().passes, workload->validationMessages()};
  return frame;
}

// Share of display channels differing by more than `tolerance`.
double shareDiffering(const ImageRGBA32F& a, const ImageRGBA32F& b, float tolerance) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  size_t differing = 0, channels = 0;
  for (size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i) {
    if (i % 4 == 3) continue;  // alpha
    ++channels;
    differing += std::abs(a.pixels[i] - b.pixels[i]) > tolerance;
  }
  return channels ? double(differing) / double(channels) : 1.0;
}

bool allFinite(const ImageRGBA32F& image) {
  return std::all_of(image.pixels.begin(), image.pixels.end(), [](float v) { return std::isfinite(v); });
}

std::string writeScene(const std::string& name, const std::string& json) {
  const auto path = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(path) << json;
  return path.string();
}

constexpr float kOneLevel = 1.5f / 255.0f;  // display values are 8-bit

// Before camera-relative rendering: FLIP mean 0.10 at 1e6 m and 0.47 at 1e7 m (blocky geometry).
TEST(Stability, AtriumTenThousandKilometresOutRendersLikeAtTheOrigin) {
  const std::string small = R"("scale": 0.05, "texture_size": 16)";
  const auto origin =
      render(writeScene("far-0.json", R"({"generator": {"type": "stress-far", "offset": 0, )" + small + "}}"), {});
  const auto far =
      render(writeScene("far-1e7.json", R"({"generator": {"type": "stress-far", "offset": 1e7, )" + small + "}}"), {});
  EXPECT_LT(shareDiffering(origin.display, far.display, kOneLevel), 0.001);
  EXPECT_EQ(origin.validationMessages + far.validationMessages, 0u);
}

// Before reversed-Z: near 1e-4 with far 1e5 z-fought (FLIP mean 0.0098); far = inf was rejected.
TEST(Stability, TinyNearPlaneAndInfiniteFarPlaneKeepTheImage) {
  const std::string scene = kScenes + "/showcase-small.json";
  const auto plain = render(scene, {});
  const auto deep = render(scene, {{"camera.near", "1e-4"}, {"camera.far", "1e5"}});
  const auto infinite = render(scene, {{"camera.near", "1e-5"}, {"camera.far", "inf"}});
  EXPECT_LT(shareDiffering(plain.display, deep.display, kOneLevel), 0.001);
  EXPECT_LT(shareDiffering(plain.display, infinite.display, kOneLevel), 0.001);
}

// Pre-exposure: lights x1e6 with the exposure / 1e6 is the same image (and the same pre-exposed
// HDR image); without it the R16F target saturated at 65504.
TEST(Stability, CompensatedLightScaleKeepsTheImage) {
  const std::string scene = kScenes + "/showcase-small.json";
  const auto plain = render(scene, {{"post.exposure", "0.6"}});
  for (const char* scale : {"1e-6", "1e6"}) {
    const double factor = std::stod(scale);
    char exposure[32];
    std::snprintf(exposure, sizeof exposure, "%.17g", 0.6 / factor);  // std::to_string keeps 6 decimals
    const auto scaled = render(scene, {{"scene.light_scale", scale}, {"post.exposure", exposure}});
    EXPECT_LT(shareDiffering(plain.display, scaled.display, kOneLevel), 0.001) << scale;
    EXPECT_LT(shareDiffering(plain.hdr, scaled.hdr, 0.01f), 0.001) << scale;
    EXPECT_TRUE(allFinite(scaled.hdr)) << scale;
  }
}

// Auto exposure: a scene a million times too bright for the fixed exposure (white) shows again.
TEST(Stability, AutoExposureShowsASceneTheFixedExposureBurnsOut) {
  const std::string scene = kScenes + "/showcase-small.json";
  const auto fixed = render(scene, {{"scene.light_scale", "1e6"}});
  const auto automatic = render(scene, {{"scene.light_scale", "1e6"}, {"post.exposure", "auto"}});
  EXPECT_GT(meanOf(fixed.display), 0.9);  // the problem: burnt out
  const double mean = meanOf(automatic.display);
  EXPECT_GT(mean, 0.05);
  EXPECT_LT(mean, 0.7);
  EXPECT_TRUE(allFinite(automatic.hdr));
  EXPECT_TRUE(std::any_of(automatic.passes.begin(), automatic.passes.end(),
                          [](const PassTiming& pass) { return pass.name == "Exposure" && !pass.culled; }));
  EXPECT_EQ(automatic.validationMessages, 0u);
  // The exposure depends on the scene, not on its absolute scale: x1 and x1e6 look the same.
  const auto unscaled = render(scene, {{"post.exposure", "auto"}});
  EXPECT_LT(shareDiffering(unscaled.display, automatic.display, kOneLevel), 0.01);
}

// NaN-safe shading: a light on the floor and roughness-0 materials (stress-nan) stay finite.
TEST(Stability, StressNanRendersNoNonFinitePixel) {
  const auto frame = render(kRepositoryScenes + "/stress-nan.json", {}, 2);
  EXPECT_TRUE(allFinite(frame.hdr));
  EXPECT_TRUE(allFinite(frame.display));
  EXPECT_GT(meanOf(frame.display), 0.01);
}

}  // namespace
}  // namespace fgb::render
