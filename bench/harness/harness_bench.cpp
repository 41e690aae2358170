// Harness speed (issue item 7). Run the full measurement with medians over repetitions:
//   build/bench/harness_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// The EXR pair is generated procedurally (3840x2160 unless FGBENCH_BENCH_WIDTH/HEIGHT say
// otherwise) into a temporary directory once per process.
#include <fgb/harness/base/parallel.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/metrics/metrics.hpp>
#include <fgb/harness/run/run_loop.hpp>

#include "fake_workload.hpp"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <sys/resource.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

namespace fgb::harness {
namespace {

uint32_t envSize(const char* name, uint32_t fallback) {
  const char* v = std::getenv(name);
  return v ? static_cast<uint32_t>(std::max(16, std::atoi(v))) : fallback;
}

// A rendered-looking HDR frame: sky gradient, textured ground, a few bright lamps (HDR range
// ~2^8), and a test copy with noise, a shifted object and a colour cast in one region.
Image syntheticFrame(uint32_t w, uint32_t h, bool test) {
  Image image = makeImage(w, h, Encoding::Linear);
  std::mt19937 rng(test ? 2 : 1);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  for (uint32_t y = 0; y < h; ++y) {
    const float v = static_cast<float>(y) / static_cast<float>(h);
    for (uint32_t x = 0; x < w; ++x) {
      const float u = static_cast<float>(x) / static_cast<float>(w);
      float* p = &image.rgba[(static_cast<std::size_t>(y) * w + x) * 4];
      const bool ground = v > 0.55f;
      const float checker = ((x / 64 + y / 64) % 2) ? 0.35f : 0.15f;
      p[0] = ground ? checker : 0.4f + 0.8f * (1.0f - v);
      p[1] = ground ? checker * 0.9f : 0.6f + 0.9f * (1.0f - v);
      p[2] = ground ? checker * 0.7f : 1.2f + 1.5f * (1.0f - v);
      const float shift = test ? 0.004f : 0.0f;
      for (int lamp = 0; lamp < 6; ++lamp) {
        const float dx = u - (0.1f + 0.15f * lamp + shift), dy = v - 0.45f;
        if (dx * dx * 16.0f + dy * dy * 9.0f < 0.0004f) p[0] = p[1] = p[2] = 60.0f;
      }
      if (test) {
        for (int c = 0; c < 3; ++c) p[c] = std::max(0.0f, p[c] * (1.0f + noise(rng)));
        if (u > 0.6f && u < 0.8f && ground) p[0] *= 1.08f;
      }
      p[3] = 1.0f;
    }
  }
  return image;
}

struct ExrPair {
  std::filesystem::path dir, reference, test;
  uint32_t width = 0, height = 0;
  ExrPair() {
    width = envSize("FGBENCH_BENCH_WIDTH", 3840);
    height = envSize("FGBENCH_BENCH_HEIGHT", 2160);
    dir = std::filesystem::temp_directory_path() / fmt::format("fgb-harness-bench-{}x{}-{}", width, height, std::random_device{}());
    std::filesystem::create_directories(dir);
    reference = dir / "reference.exr";
    test = dir / "test.exr";
    writeExr(reference, syntheticFrame(width, height, false));
    writeExr(test, syntheticFrame(width, height, true));
  }
  ~ExrPair() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

const ExrPair& pair() {
  static const ExrPair instance;
  return instance;
}

void setCounters(benchmark::State& state) {
  state.counters["pixels"] = static_cast<double>(pair().width) * pair().height;
}

// What `fgbench compare A B` does, in process: read both EXRs, all metrics including HDR-FLIP.
void BM_CompareInProcess(benchmark::State& state) {
  const ExrPair& p = pair();
  double flipMean = 0.0;
  int exposures = 0;
  for (auto _ : state) {
    const auto [a, b] = readImagePair(p.reference, p.test);
    const Comparison c = compareImages(a, b);
    flipMean = c.metrics.flip->mean;
    exposures = c.metrics.flip->exposures;
    benchmark::DoNotOptimize(c.errorMap.data());
  }
  setCounters(state);
  state.counters["flip_mean"] = flipMean;
  state.counters["exposures"] = exposures;
}
BENCHMARK(BM_CompareInProcess)->Unit(benchmark::kMillisecond)->UseRealTime();

// CPU seconds (user + system) used by finished child processes so far: on a shared machine the
// fairer comparison between two commands than wall time alone.
double childCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

int runCommand(benchmark::State& state, const std::string& command) {
  const int status = std::system((command + " > /dev/null 2>&1").c_str());
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 127 || code < 0) state.SkipWithError(("could not run: " + command).c_str());
  return code;
}

// The command line itself, process start-up included, as a user runs it.
void BM_FgbenchCompareCli(benchmark::State& state) {
#ifdef FGBENCH_BINARY
  const ExrPair& p = pair();
  const std::string command = fmt::format("'{}' compare '{}' '{}'", FGBENCH_BINARY, p.reference.string(), p.test.string());
  const double cpuBefore = childCpuSeconds();
  for (auto _ : state) {
    if (runCommand(state, command) > 1) break;  // 0 ok, 1 "check failed" are both complete runs
  }
  state.counters["child_cpu_s"] = (childCpuSeconds() - cpuBefore) / static_cast<double>(state.iterations());
  setCounters(state);
#else
  state.SkipWithError("fgbench was not built in this configuration");
#endif
}
BENCHMARK(BM_FgbenchCompareCli)->Unit(benchmark::kMillisecond)->UseRealTime();

// The reference point: OpenImageIO's `oiiotool --diff` on the same pair (exit 1 = images differ).
void BM_OiiotoolDiff(benchmark::State& state) {
#ifdef OIIOTOOL_BINARY
  const ExrPair& p = pair();
  const std::string command = fmt::format("'{}' --diff '{}' '{}'", OIIOTOOL_BINARY, p.reference.string(), p.test.string());
  const double cpuBefore = childCpuSeconds();
  for (auto _ : state) {
    if (runCommand(state, command) > 2) break;
  }
  state.counters["child_cpu_s"] = (childCpuSeconds() - cpuBefore) / static_cast<double>(state.iterations());
  setCounters(state);
#else
  state.SkipWithError("oiiotool not found");
#endif
}
BENCHMARK(BM_OiiotoolDiff)->Unit(benchmark::kMillisecond)->UseRealTime();

// FLIP alone on the decoded pair, with 1 thread and with all of them (FGBENCH_THREADS).
void BM_HdrFlipThreads(benchmark::State& state) {
  static const Image a = readImage(pair().reference);
  static const Image b = readImage(pair().test);
  const std::string threads = std::to_string(state.range(0));
  if (state.range(0) > 0) setenv("FGBENCH_THREADS", threads.c_str(), 1);
  for (auto _ : state) benchmark::DoNotOptimize(hdrFlip(a, b).map.error.data());
  unsetenv("FGBENCH_THREADS");
  state.counters["threads"] = state.range(0) > 0 ? static_cast<double>(state.range(0)) : workerCount();
  setCounters(state);
}
BENCHMARK(BM_HdrFlipThreads)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LdrFlip(benchmark::State& state) {
  static const Image a = toEncoding(readImage(pair().reference), Encoding::Srgb);
  static const Image b = toEncoding(readImage(pair().test), Encoding::Srgb);
  for (auto _ : state) benchmark::DoNotOptimize(ldrFlip(a, b).error.data());
  setCounters(state);
}
BENCHMARK(BM_LdrFlip)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReadExrPair(benchmark::State& state) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(readImage(pair().reference).rgba.data());
    benchmark::DoNotOptimize(readImage(pair().test).rgba.data());
  }
  setCounters(state);
}
BENCHMARK(BM_ReadExrPair)->Unit(benchmark::kMillisecond)->UseRealTime();

// The harness' own cost per frame around rendering (bookkeeping, timing, statistics), with a
// workload that does no rendering at all: this is what `run` adds on top of GPU/driver time.
void BM_RunLoopOverhead(benchmark::State& state) {
  const auto frames = static_cast<uint32_t>(state.range(0));
  double harnessUsPerFrame = 0.0;
  for (auto _ : state) {
    testing::FakeWorkload workload;
    const RunResult run = runBenchmark(workload, RunOptions{0, frames, kDefaultUnstableSpread, {}});
    harnessUsPerFrame = run.overhead.perFrameUs;
    benchmark::DoNotOptimize(run.passes.data());
  }
  state.SetItemsProcessed(state.iterations() * frames);
  state.counters["harness_us_per_frame"] = harnessUsPerFrame;
}
BENCHMARK(BM_RunLoopOverhead)->Arg(64)->Arg(1024)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fgb::harness

BENCHMARK_MAIN();
