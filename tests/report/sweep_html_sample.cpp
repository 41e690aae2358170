// Writes the sweep outputs of a crafted sweep into the folder given as the only argument, for the
// browser test of sweep.html (tests/report): 16 configurations (msaa 1, 2, 4, 8 x four
// lighting.max_per_cluster values) whose points fall in four tight clusters, one per MSAA, with
// frame times of seconds (lavapipe's atrium at 640x360) and labels long enough to collide.
#include <cmath>
#include <exception>
#include <fgb/harness/sweep/sweep.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>
#include <iostream>
#include <memory>
#include <string>

namespace {

using namespace fgb;

constexpr uint32_t kWidth = 96, kHeight = 54;

// Rendering costs nothing; the times and images depend on the configuration's knobs like a real
// renderer's would: MSAA costs time and removes error, the per-cluster cap costs a little time and
// removes a little error up to 16 lights.
class CraftedWorkload final : public render::Workload {
 public:
  explicit CraftedWorkload(const render::WorkloadConfig& config) {
    device_.name = "crafted";
    device_.driver = "sweep_html_sample";
    device_.type = "cpu";
    const auto knob = [&](const char* key, double fallback) {
      const auto it = config.knobs.find(key);
      return it == config.knobs.end() ? fallback : std::stod(it->second);
    };
    const double msaaSteps = std::log2(std::max(config.msaa, 1u));
    const double capSteps = std::log2(knob("lighting.max_per_cluster", 4)) / 2;
    reference_ = knob("render.ssaa", 1) > 1;
    // A cap of 16 lights is as good as any higher one: 64 and 256 cost time for nothing (dominated).
    frameMs_ = 1900 + 420 * msaaSteps + 40 * capSteps;
    quality_ = reference_ ? 1.0 : 0.2 + 0.22 * msaaSteps + (capSteps >= 2 ? 0.01 : 0.0);
  }
  const render::DeviceDescription& device() const override { return device_; }
  render::FrameTiming renderFrame() override {
    const double ms = frameMs_ * (1 + 0.002 * static_cast<double>(frame_++ % 7));
    return {{{"Mesh Render", "graphics", false, 0.7 * ms, 0}, {"Bloom", "graphics", false, 0.3 * ms, 0.7 * ms}}, ms, 1};
  }
  std::vector<render::FrameTiming> finish() override { return {}; }
  render::ImageRGBA32F readHdr() override { return image(2.0f); }
  render::ImageRGBA32F readDisplay() override { return image(1.0f); }
  std::string graphviz(render::GraphDetail) const override { return {}; }
  std::map<std::string, double> stats() const override { return {}; }
  uint64_t validationMessages() const override { return 0; }

 private:
  // Stripes whose hard edges soften with quality (the reference's are smooth).
  render::ImageRGBA32F image(float scale) const {
    render::ImageRGBA32F img{kWidth, kHeight, std::vector<float>(std::size_t{kWidth} * kHeight * 4)};
    for (uint32_t y = 0; y < kHeight; ++y) {
      for (uint32_t x = 0; x < kWidth; ++x) {
        const double edge = std::sin(0.3 * x + 0.5 * y);
        const double v = quality_ * (0.5 + 0.5 * edge) + (1 - quality_) * (edge > 0 ? 1.0 : 0.0);
        float* p = &img.pixels[(std::size_t{y} * kWidth + x) * 4];
        p[0] = scale * static_cast<float>(v);
        p[1] = scale * static_cast<float>(0.8 * v);
        p[2] = scale * 0.2f;
        p[3] = 1.0f;
      }
    }
    return img;
  }
  render::DeviceDescription device_;
  bool reference_ = false;
  double frameMs_ = 0, quality_ = 0;
  uint32_t frame_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: sweep_html_sample OUTPUT_FOLDER\n";
    return 2;
  }
  try {
    render::WorkloadConfig base;
    base.scenePath = "crafted.json";
    harness::SweepPlan plan;
    plan.scene = base.scenePath;
    plan.configurations = harness::expandGrid(
        base, {harness::parseVary("msaa=1,2,4,8"), harness::parseVary("lighting.max_per_cluster=4,16,64,256")});
    plan.warmup = 2;
    plan.frames = 24;
    const auto open = [](const render::WorkloadConfig& c) { return std::make_unique<CraftedWorkload>(c); };
    harness::SweepResult result = harness::runSweep(open, plan);
    result.toolVersion = "sample";
    result.axes = {harness::parseVary("msaa=1,2,4,8"), harness::parseVary("lighting.max_per_cluster=4,16,64,256")};
    harness::writeSweepOutputs(argv[1], result);
    std::cout << harness::sweepTable(result);
  } catch (const std::exception& e) {
    std::cerr << "sweep_html_sample: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
