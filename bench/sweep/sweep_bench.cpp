// The sweep's own cost beyond rendering, per phase, at the sizes sweeps run at (640x360 on lavapipe,
// 1920x1080 on a GPU) and 4 or 16 configurations. The workload renders nothing: its frame times are
// made up and its images are computed once and copied out on every readback, so what is measured is
// the sweep engine's bookkeeping, reference handling, metrics, statistics and report writing.
//
//   build/bench/sweep_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Rows (arguments: width/height/configurations):
//   BM_Sweep                 a whole runSweep (open, references, warm-up, 32 measured frames per
//                            configuration in rounds, metrics, front), reports not written;
//   BM_SweepReference        one reference: two renders' readbacks, the bit-identity check and the
//                            noise floor's two comparisons;
//   BM_SweepMetrics          every configuration against its reference (LDR-FLIP + heat map, HDR-FLIP,
//                            RMSE, PSNR);
//   BM_SweepStatistics       each configuration's median interval and run summary, the stability test,
//                            Mann-Whitney dominance and the front;
//   BM_SweepReport           sweep.json, .csv, .md and .html (PNG thumbnails) written to a temp folder.
#include <benchmark/benchmark.h>

#include <cmath>
#include <fgb/harness/sweep/sweep.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <tuple>

namespace fgb::harness {
namespace {

constexpr uint32_t kMeasuredFrames = 32;

// A frame with edges and lamps; `quality` in [0, 1] blends hard, noisy edges (0) towards the
// reference's smooth ones (1), as anti-aliasing does.
render::ImageRGBA32F frame(uint32_t width, uint32_t height, double quality, float scale) {
  render::ImageRGBA32F img{width, height, std::vector<float>(std::size_t{width} * height * 4)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  const float q = static_cast<float>(quality);
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      const float edge = std::sin(0.05f * static_cast<float>(x) + 0.11f * static_cast<float>(y));
      const float hard = edge > 0 ? 1.0f : 0.0f, soft = 0.5f + 0.5f * edge;
      const float v = q * soft + (1.0f - q) * (hard + 0.05f * jitter(rng));
      float* p = &img.pixels[(std::size_t{y} * width + x) * 4];
      p[0] = scale * v;
      p[1] = scale * v * 0.8f;
      p[2] = scale * 0.3f;
      p[3] = 1.0f;
    }
  }
  return img;
}

// Images by (width, height, quality, scale), computed once: a readback then costs one copy.
const render::ImageRGBA32F& cachedFrame(uint32_t width, uint32_t height, double quality, float scale) {
  static std::map<std::tuple<uint32_t, uint32_t, double, float>, render::ImageRGBA32F> cache;
  const auto key = std::make_tuple(width, height, quality, scale);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, frame(width, height, quality, scale)).first;
  return it->second;
}

// Renders nothing: frame times grow with the configuration's index, images are the cached frames;
// the reference (render.ssaa set) has quality 1.
class InstantWorkload : public render::Workload {
 public:
  explicit InstantWorkload(const render::WorkloadConfig& config) : width_(config.width), height_(config.height) {
    device_.name = "instant";
    device_.type = "cpu";
    const auto cap = config.knobs.find("lighting.max_per_cluster");
    const double step = cap == config.knobs.end() ? 0.0 : std::log2(std::stod(cap->second));
    quality_ =
        config.knobs.count("render.ssaa") ? 1.0 : std::min(0.9, 0.1 + 0.05 * step + 0.1 * std::log2(config.msaa));
    frameMs_ = 1.0 + 0.2 * step + 0.5 * config.msaa;
  }
  const render::DeviceDescription& device() const override { return device_; }
  render::FrameTiming renderFrame() override {
    render::FrameTiming t;
    const double ms = frameMs_ + 0.01 * static_cast<double>(frame_++ % 13);
    for (const char* pass : {"Cull", "Mesh Render", "Bloom", "Tone mapping"})
      t.passes.push_back({pass, "graphics", false, ms / 4, -1.0});
    t.gpuFrameMs = ms;
    return t;
  }
  std::vector<render::FrameTiming> finish() override { return {}; }
  render::ImageRGBA32F readHdr() override { return cachedFrame(width_, height_, quality_, 4.0f); }
  render::ImageRGBA32F readDisplay() override { return cachedFrame(width_, height_, quality_, 1.0f); }
  std::string graphviz(render::GraphDetail) const override { return ""; }
  std::map<std::string, double> stats() const override { return {}; }
  uint64_t validationMessages() const override { return 0; }

 private:
  uint32_t width_, height_;
  double quality_ = 0, frameMs_ = 0;
  uint32_t frame_ = 0;
  render::DeviceDescription device_;
};

const WorkloadOpener kOpen = [](const render::WorkloadConfig& c) { return std::make_unique<InstantWorkload>(c); };

// msaa=1,4 x lighting.max_per_cluster (4 configurations: 4,64; 16: 4,16,64,256, x msaa=1,2,4,8).
SweepPlan plan(const benchmark::State& state) {
  render::WorkloadConfig base;
  base.scenePath = "bench.json";
  base.width = static_cast<uint32_t>(state.range(0));
  base.height = static_cast<uint32_t>(state.range(1));
  const bool sixteen = state.range(2) >= 16;
  SweepPlan p;
  p.scene = base.scenePath;
  p.configurations =
      expandGrid(base, {parseVary(sixteen ? "msaa=1,2,4,8" : "msaa=1,4"),
                        parseVary(sixteen ? "lighting.max_per_cluster=4,16,64,256" : "lighting.max_per_cluster=4,64")});
  p.warmup = 2;
  p.frames = kMeasuredFrames;
  p.roundFrames = 16;
  return p;
}

void label(benchmark::State& state) {
  state.SetLabel(std::to_string(state.range(0)) + "x" + std::to_string(state.range(1)) + ", " +
                 std::to_string(state.range(2)) + " configurations");
}

// One measured sweep per argument set, kept for the phases that work on its result.
const SweepResult& measured(const benchmark::State& state) {
  static std::map<std::tuple<int64_t, int64_t, int64_t>, SweepResult> results;
  const auto key = std::make_tuple(state.range(0), state.range(1), state.range(2));
  auto it = results.find(key);
  if (it == results.end()) it = results.emplace(key, runSweep(kOpen, plan(state))).first;
  return it->second;
}

void BM_Sweep(benchmark::State& state) {
  const SweepPlan p = plan(state);
  for (auto _ : state) benchmark::DoNotOptimize(runSweep(kOpen, p));
  label(state);
}

void BM_SweepReference(benchmark::State& state) {
  const render::WorkloadConfig reference = referenceOf(plan(state).configurations.front());
  for (auto _ : state) benchmark::DoNotOptimize(renderReference(kOpen, reference, 2));
  label(state);
}

void BM_SweepMetrics(benchmark::State& state) {
  SweepResult result = measured(state);
  for (auto _ : state) compareWithReferences(result);
  label(state);
}

void BM_SweepStatistics(benchmark::State& state) {
  SweepResult result = measured(state);
  const StabilityRule rule;
  for (auto _ : state) {
    for (auto& c : result.configurations) {
      c.frameGpu = medianConfidenceInterval(c.run.frameGpuMs);
      summarizeRun(c.run);
      c.stable = isStable(c.run, rule);
    }
    markFront(result);
  }
  label(state);
}

void BM_SweepReport(benchmark::State& state) {
  SweepResult result = measured(state);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "fgbench-sweep-bench";
  for (auto _ : state) writeSweepOutputs(dir, result);
  std::filesystem::remove_all(dir);
  label(state);
}

// (width, height, configurations): the lavapipe size and the GPU size, 4 and 16 configurations.
void sizes(benchmark::internal::Benchmark* b) {
  for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1920, 1080}}) {
    for (int configurations : {4, 16}) b->Args({w, h, configurations});
  }
  b->ArgNames({"w", "h", "configs"})->Unit(benchmark::kMillisecond);
}

// A sweep of any size has one reference here (the configurations differ in speed-only knobs and MSAA).
void sizesOneReference(benchmark::internal::Benchmark* b) {
  for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1920, 1080}}) b->Args({w, h, 4});
  b->ArgNames({"w", "h", "configs"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Sweep)->Apply(sizes);
BENCHMARK(BM_SweepReference)->Apply(sizesOneReference);
BENCHMARK(BM_SweepMetrics)->Apply(sizes);
BENCHMARK(BM_SweepStatistics)->Apply(sizes);
BENCHMARK(BM_SweepReport)->Apply(sizes);

}  // namespace
}  // namespace fgb::harness

BENCHMARK_MAIN();
