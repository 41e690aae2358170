// The proof scene end to end: compute -> draw (MSAA + resolve) -> tone map -> readback, with a
// culled debug node, under validation + synchronization validation.
#include "gpu_support.hpp"

#include <fgb/renderer/workload.hpp>

#include <cmath>

namespace fgb::test {
namespace {

struct Rgb {
  float r, g, b;
};

Rgb pixel(const render::ImageRGBA32F& image, uint32_t x, uint32_t y) {
  const float* p = &image.pixels[(size_t{y} * image.width + x) * 4];
  return {p[0], p[1], p[2]};
}

// Pixel of normalised device coordinates (x right, y down as Vulkan's viewport maps them).
std::pair<uint32_t, uint32_t> pixelOf(float ndcX, float ndcY, uint32_t width, uint32_t height) {
  return {static_cast<uint32_t>((ndcX + 1) * 0.5f * width), static_cast<uint32_t>((ndcY + 1) * 0.5f * height)};
}

// A point well inside triangle `index` of the fan (12 triangles, radius 0.8, not animated).
std::pair<uint32_t, uint32_t> insideTriangle(uint32_t index, uint32_t width, uint32_t height) {
  const float angle = 6.2831853f * (static_cast<float>(index) + 0.5f) / 12.0f;
  return pixelOf(0.45f * std::cos(angle), 0.45f * std::sin(angle), width, height);
}

float toneMapped(float hdr) { return 1.0f - std::exp(-hdr * 0.6f); }

void expectNear(Rgb actual, Rgb expected, float tolerance, const char* what) {
  EXPECT_NEAR(actual.r, expected.r, tolerance) << what;
  EXPECT_NEAR(actual.g, expected.g, tolerance) << what;
  EXPECT_NEAR(actual.b, expected.b, tolerance) << what;
}

std::unique_ptr<render::Workload> openProof(uint32_t msaa, const std::string& queues) {
  render::WorkloadConfig config;
  config.scenePath = "builtin:proof";
  config.device = testDeviceSelector();
  config.msaa = msaa;
  config.validation = true;
  config.knobs["queues"] = queues;
  // Several queues stay apart even on a one-queue device: submits and semaphores get exercised.
  if (queues != "0") config.knobs["separate-queues"] = "1";
  return render::openWorkload(config);
}

class Proof : public ::testing::TestWithParam<std::tuple<uint32_t, std::string>> {};

TEST_P(Proof, RendersKnownPixelsWithNoValidationMessages) {
  const auto [msaa, queues] = GetParam();
  auto workload = openProof(msaa, queues);
  std::vector<render::FrameTiming> timings;
  for (int frame = 0; frame < 4; ++frame) {
    auto t = workload->renderFrame();
    if (!t.passes.empty()) timings.push_back(std::move(t));
  }
  for (auto& t : workload->finish()) timings.push_back(std::move(t));
  EXPECT_EQ(timings.size(), 4u) << "every frame's timings come back exactly once";

  const auto hdr = workload->readHdr();
  const auto display = workload->readDisplay();
  ASSERT_EQ(hdr.width, 320u);
  ASSERT_EQ(hdr.height, 180u);
  ASSERT_EQ(display.pixels.size(), hdr.pixels.size());

  const auto [bx, by] = std::pair{2u, 2u};  // corner: background
  expectNear(pixel(hdr, bx, by), {0.02f, 0.02f, 0.05f}, 1e-3f, "background HDR");
  expectNear(pixel(display, bx, by), {toneMapped(0.02f), toneMapped(0.02f), toneMapped(0.05f)}, 4e-3f,
             "background display");
  const auto [ex, ey] = insideTriangle(0, 320, 180);  // even triangles: bright HDR orange
  expectNear(pixel(hdr, ex, ey), {4.0f, 1.0f, 0.25f}, 1e-2f, "even triangle HDR");
  expectNear(pixel(display, ex, ey), {toneMapped(4.0f), toneMapped(1.0f), toneMapped(0.25f)}, 1e-2f,
             "even triangle display");
  const auto [ox, oy] = insideTriangle(1, 320, 180);  // odd triangles: blue
  expectNear(pixel(hdr, ox, oy), {0.1f, 0.4f, 1.0f}, 1e-2f, "odd triangle HDR");
  expectNear(pixel(display, ox, oy), {toneMapped(0.1f), toneMapped(0.4f), toneMapped(1.0f)}, 1e-2f,
             "odd triangle display");
  EXPECT_EQ(workload->validationMessages(), 0u) << "validation reported problems (see stderr)";
}

INSTANTIATE_TEST_SUITE_P(MsaaAndQueues, Proof,
                         testing::Values(std::tuple{4u, std::string("0")}, std::tuple{1u, std::string("0")},
                                         std::tuple{4u, std::string("3")}));

TEST(ProofGraph, DebugNodeIsCulledAndTimingsArePerNode) {
  auto workload = openProof(4, "0");
  workload->renderFrame();
  workload->renderFrame();
  auto timings = workload->finish();
  ASSERT_FALSE(timings.empty());
  const auto& frame = timings.back();
  ASSERT_EQ(frame.passes.size(), 5u);
  double sum = 0;
  for (const auto& pass : frame.passes) {
    if (pass.name == "Debug luminance") {
      EXPECT_TRUE(pass.culled);
      EXPECT_EQ(pass.gpuMs, 0.0);
      continue;
    }
    EXPECT_FALSE(pass.culled) << pass.name;
    EXPECT_GE(pass.gpuMs, 0.0) << pass.name;
    EXPECT_GE(pass.gpuStartMs, 0.0) << pass.name;
    EXPECT_LE(pass.gpuStartMs + pass.gpuMs, frame.gpuFrameMs + 1e-6) << pass.name;
    sum += pass.gpuMs;
  }
  EXPECT_GT(sum, 0.0) << "timestamps measured nothing";
  EXPECT_GT(frame.gpuFrameMs, 0.0);
  EXPECT_EQ(frame.passes[0].queue, "compute");
  EXPECT_EQ(frame.passes[3].queue, "transfer");

  const std::string dot = workload->graphviz(render::GraphDetail::Full);
  EXPECT_NE(dot.find("Debug luminance"), std::string::npos);
  EXPECT_NE(dot.find("digraph"), std::string::npos);
  EXPECT_EQ(workload->validationMessages(), 0u);
}

}  // namespace
}  // namespace fgb::test
