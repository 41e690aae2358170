// The sweep's overhead beyond rendering. Run the measurement with
//   build/bench/sweep_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// Images are 640x360 unless FGBENCH_BENCH_WIDTH/HEIGHT say otherwise (the lavapipe sweep's size).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <fgb/harness/sweep.hpp>
#include <fgb/harness/sweep_report.hpp>
#include <random>

namespace fgb::harness {
namespace {

uint32_t envSize(const char* name, uint32_t fallback) {
  const char* v = std::getenv(name);
  return v ? static_cast<uint32_t>(std::max(16, std::atoi(v))) : fallback;
}
const uint32_t kWidth = envSize("FGBENCH_BENCH_WIDTH", 640);
const uint32_t kHeight = envSize("FGBENCH_BENCH_HEIGHT", 360);

// A frame with edges and lamps; `quality` in [0, 1] blends hard, noisy edges (0) towards the
// reference's smooth ones (1), as anti-aliasing does.
render::ImageRGBA32F frame(double quality, float scale) {
  render::ImageRGBA32F img{kWidth, kHeight, std::vector<float>(std::size_t{kWidth} * kHeight * 4)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  for (uint32_t y = 0; y < kHeight; ++y) {
    for (uint32_t x = 0; x < kWidth; ++x) {
      const float edge = std::sin(0.05f * static_cast<float>(x) + 0.11f * static_cast<float>(y));
      const float hard = edge > 0 ? 1.0f : 0.0f, soft = 0.5f + 0.5f * edge;
      const float v =
          static_cast<float>(quality) * soft + (1.0f - static_cast<float>(quality)) * (hard + 0.05f * jitter(rng));
      float* p = &img.pixels[(std::size_t{y} * kWidth + x) * 4];
      p[0] = scale * v;
      p[1] = scale * v * 0.8f;
      p[2] = scale * 0.3f;
      p[3] = 1.0f;
    }
  }
  return img;
}

// Renders nothing: frame times are made up (growing with MSAA), images are precomputed per MSAA.
class InstantWorkload : public render::Workload {
 public:
  explicit InstantWorkload(uint32_t msaa) : msaa_(msaa) {
    device_.name = "instant";
    device_.type = "cpu";
  }
  const render::DeviceDescription& device() const override { return device_; }
  render::FrameTiming renderFrame() override {
    render::FrameTiming t;
    const double ms = msaa_ + 0.01 * static_cast<double>(frame_++ % 13);
    for (const char* pass : {"Cull", "Mesh Render", "Bloom", "Tone mapping"})
      t.passes.push_back({pass, "graphics", false, ms / 4, -1.0});
    t.gpuFrameMs = ms;
    return t;
  }
  std::vector<render::FrameTiming> finish() override { return {}; }
  render::ImageRGBA32F readHdr() override { return image(4.0f); }
  render::ImageRGBA32F readDisplay() override { return image(1.0f); }
  std::string graphviz(render::GraphDetail) const override { return ""; }
  std::map<std::string, double> stats() const override { return {{"msaa", msaa_}}; }
  uint64_t validationMessages() const override { return 0; }

 private:
  render::ImageRGBA32F image(float scale) const {
    const double quality = msaa_ >= 8 ? 1.0 : std::log2(static_cast<double>(msaa_)) / 3.0;
    return frame(quality, scale);
  }
  uint32_t msaa_;
  uint32_t frame_ = 0;
  render::DeviceDescription device_;
};

SweepPlan plan(uint32_t frames) {
  render::WorkloadConfig base;
  base.scenePath = "bench.json";
  SweepPlan p;
  p.scene = base.scenePath;
  p.configurations = expandGrid(base, {parseVary("msaa=1,2,4,8")});
  p.warmup = 2;
  p.frames = frames;
  return p;
}

const WorkloadOpener kOpen = [](const render::WorkloadConfig& c) { return std::make_unique<InstantWorkload>(c.msaa); };

// A whole sweep of 4 configurations x N frames with rendering costing nothing.
void BM_SweepWithoutRendering(benchmark::State& state) {
  const SweepPlan p = plan(static_cast<uint32_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(runSweep(kOpen, p));
  state.SetLabel(std::to_string(kWidth) + "x" + std::to_string(kHeight) + ", 4 configurations");
}
BENCHMARK(BM_SweepWithoutRendering)->Arg(64)->Arg(512)->Unit(benchmark::kMillisecond);

SweepResult measured() {
  static const SweepResult result = runSweep(kOpen, plan(128));
  return result;
}

// FLIP (LDR and HDR), RMSE, PSNR and heat maps of 4 configurations against the reference.
void BM_SweepCompareWithReference(benchmark::State& state) {
  SweepResult result = measured();
  for (auto _ : state) compareWithReferences(result);
}
BENCHMARK(BM_SweepCompareWithReference)->Unit(benchmark::kMillisecond);

// Mann–Whitney dominance over every pair and the front (4 configurations x 128 frames).
void BM_SweepFront(benchmark::State& state) {
  SweepResult result = measured();
  for (auto _ : state) markFront(result);
}
BENCHMARK(BM_SweepFront)->Unit(benchmark::kMicrosecond);

// sweep.json + sweep.csv + sweep.md + sweep.html (inline PNG thumbnails) as text.
void BM_SweepReports(benchmark::State& state) {
  const SweepResult result = measured();
  for (auto _ : state) {
    benchmark::DoNotOptimize(sweepJson(result).dump());
    benchmark::DoNotOptimize(sweepCsv(result));
    benchmark::DoNotOptimize(sweepMarkdown(result));
    benchmark::DoNotOptimize(sweepHtml(result));
  }
}
BENCHMARK(BM_SweepReports)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fgb::harness

BENCHMARK_MAIN();
