// A benchmark run's results and its files: timings.json (contract schema, plus per-frame samples
// so `compare-runs` can test significance) and timings.csv (one row per pass per frame).
#pragma once

#include <fgb/harness/results/async_check.hpp>
#include <fgb/harness/results/budget.hpp>
#include <fgb/harness/results/clock_check.hpp>
#include <fgb/harness/results/golden.hpp>
#include <fgb/harness/stats/stats.hpp>
#include <fgb/renderer/workload.hpp>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

inline constexpr int kTimingsSchema = 1;

struct PassRecord {
  std::string name;
  std::string queue;
  bool culled = false;
  std::vector<double> samplesMs;  // one per measured frame (empty when culled)
  std::vector<double> startMs;    // start offsets within the frame when the workload reports them
  Summary gpu;
  bool unstable = false;
  std::optional<render::NonFiniteCounts> nonFinite;  // --check-finite: this pass's counts (last frame)
  // The calibration (Workload::renderIsolatedFrame): the pass alone on an idle device, one sample
  // per calibration frame; empty without one (--no-isolate, older timings.json files).
  std::vector<double> isolatedMs;
  Summary isolated;
  // How much shorter the frame's critical path would be without the pass (share of its length,
  // over the compiled schedule weighted by isolated medians); < 0 when unknown.
  double criticalShare = -1.0;
  // What budgets and compare-runs judge: the isolated median where there is one, else the span's.
  [[nodiscard]] bool hasIsolated() const { return !isolatedMs.empty(); }
  [[nodiscard]] const std::vector<double>& judgedSamples() const { return hasIsolated() ? isolatedMs : samplesMs; }
};

// A pass record with its name, queue and culled flag (and samples, for tests); the rest empty.
inline PassRecord passRecord(std::string name, std::string queue, bool culled, std::vector<double> samplesMs = {}) {
  PassRecord record;
  record.name = std::move(name);
  record.queue = std::move(queue);
  record.culled = culled;
  record.samplesMs = std::move(samplesMs);
  return record;
}

// Host time around rendering, reported apart from GPU time: opening the workload (start-up, with
// its phases), the measured loop (wall time, time inside the workload's calls, and the harness'
// own share: bookkeeping, progress), reading the images back and encoding the outputs.
struct HarnessOverhead {
  double openMs = 0.0;
  render::StartupTimes startup;
  double loopWallMs = 0.0;
  double workloadCallsMs = 0.0;
  double harnessMs = 0.0;
  double perFrameUs = 0.0;
  double readbackMs = 0.0;
  double encodeMs = 0.0;  // EXR + PNG
  double calibrationMs = 0.0;  // the isolated-cost calibration frames, after the measured loop
};

struct RunConfig {
  uint32_t width = 0, height = 0, msaa = 0, frames = 0, warmup = 0;
  std::map<std::string, std::string> knobs;
};

struct RunResult {
  std::string toolVersion;
  std::string scene;
  std::string sceneHash;
  render::DeviceDescription device;
  RunConfig config;
  std::map<std::string, double> stats;
  std::vector<PassRecord> passes;  // declaration order
  std::vector<double> frameGpuMs, frameCpuMs;
  std::vector<double> framePathTimeS;  // along a camera path: each measured frame's path time (else empty)
  Summary frameGpu, frameCpu;
  // Per measured frame: vkQueueSubmit's host time, and the nodes recorded and reused (kept
  // command buffers). Their medians land in frameSubmit and stats nodes_recorded/nodes_reused.
  std::vector<double> frameSubmitMs, nodesRecorded, nodesReused;
  Summary frameSubmit;
  HarnessOverhead overhead;
  uint32_t isolatedFrames = 0;  // calibration frames behind PassRecord::isolatedMs (0: none)
  WallClock wallClock;      // the spans against the wall time per measured frame
  DeviceState deviceState;  // clocks and temperature at the start and end of measurement
  // render.async measured (compareAsyncCompute); queues == 0 when the run did not look.
  AsyncComparison asyncCompute;
  std::optional<BudgetResult> budget;
  std::optional<GoldenResult> golden;
  bool checkedFinite = false;                       // --check-finite was on
  std::vector<render::NonFiniteCounts> nonFinite;   // checked passes, in execution order
  // Per-pass goldens (passes room), when the frame golden failed and the golden has them: the
  // first-difference verdict in one line, and timings.json "passes_golden" (null: not compared).
  std::string firstDifference;
  nlohmann::json passesGolden;

  const PassRecord* findPass(const std::string& name) const;
  // The first checked pass (execution order) that wrote a NaN, Inf or value above half of R16F's
  // maximum; null when none did (or nothing was checked).
  const render::NonFiniteCounts* firstNonFinite() const;
  MeasuredMedians medians() const;
  // Along a camera path: the measured frames' indices, slowest GPU frame first (at most `count`).
  std::vector<std::size_t> slowestFrames(std::size_t count) const;
};

// Fills the summaries and the unstable flags from the samples.
void summarizeRun(RunResult& run, double unstableSpread = kDefaultUnstableSpread);

nlohmann::json toJson(const RunResult& run);
std::string toCsv(const RunResult& run);

// Timings of a previous run, for compare-runs. Needs schema 1 and per-frame samples; anything
// else is InputError naming the file and field.
struct LoadedTimings {
  std::string file;
  std::string scene;
  std::string deviceName;
  std::string deviceType;  // "cpu", "discrete", "integrated", ... ("" when the file has none)
  std::vector<PassRecord> passes;  // with samples
  std::vector<double> frameGpuMs;
  std::vector<double> framePathTimeS;  // a path run's frame times (empty for a still camera)
};
LoadedTimings loadTimings(const std::filesystem::path& path);

}  // namespace fgb::harness
