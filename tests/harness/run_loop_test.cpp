#include <fgb/core/error.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/run/run_loop.hpp>

#include "fake_workload.hpp"

#include <gtest/gtest.h>

namespace fgb::harness {
namespace {

TEST(RunLoop, DropsWarmupAndKeepsMeasuredFramesInOrder) {
  testing::FakeWorkload workload;
  RunOptions options;
  options.warmup = 3;
  options.frames = 5;
  const RunResult run = runBenchmark(workload, options);
  EXPECT_EQ(workload.rendered(), 8u);
  ASSERT_EQ(run.frameGpuMs.size(), 5u);
  ASSERT_EQ(run.passes.size(), 3u);
  EXPECT_EQ(run.passes[0].name, "Cull");
  EXPECT_EQ(run.passes[0].queue, "compute");
  // Frame numbers 3..7 were kept: Cull took 0.1 + f ms.
  EXPECT_DOUBLE_EQ(run.passes[0].samplesMs.front(), 3.1);
  EXPECT_DOUBLE_EQ(run.passes[0].samplesMs.back(), 7.1);
  EXPECT_DOUBLE_EQ(run.passes[0].gpu.median, 5.1);
  EXPECT_EQ(run.passes[0].gpu.n, 5u);
  EXPECT_DOUBLE_EQ(run.frameCpu.min, 5.0);
  EXPECT_EQ(run.passes[1].startMs.size(), 5u);  // start offsets reported for "Draw"
  EXPECT_TRUE(run.passes[0].startMs.size() == 5u);
}

TEST(RunLoop, KeepsNodesRecordedAndReusedAndSubmitTimePerFrame) {
  testing::FakeWorkload workload;
  const RunResult run = runBenchmark(workload, RunOptions{0, 5, kDefaultUnstableSpread, {}});
  EXPECT_EQ(run.nodesRecorded, (std::vector<double>{3, 3, 1, 1, 1}));
  EXPECT_EQ(run.nodesReused, (std::vector<double>{0, 0, 2, 2, 2}));
  EXPECT_DOUBLE_EQ(run.stats.at("nodes_recorded"), 1.0);  // medians
  EXPECT_DOUBLE_EQ(run.stats.at("nodes_reused"), 2.0);
  const nlohmann::json json = toJson(run);
  EXPECT_EQ(json["samples"]["nodes_recorded"].size(), 5u);
  EXPECT_DOUBLE_EQ(json["frame_submit_ms"]["median"].get<double>(), 0.5);
  EXPECT_TRUE(json.contains("frame_cpu_ms"));  // unchanged beside it
}

TEST(RunLoop, TimesTheMeasuredFramesByTheWallClock) {
  testing::FakeWorkload workload;
  const RunResult run = runBenchmark(workload, RunOptions{2, 6, kDefaultUnstableSpread, {}});
  EXPECT_EQ(run.wallClock.frames, 6u);
  EXPECT_GT(run.wallClock.wallMsPerFrame, 0.0);
  EXPECT_DOUBLE_EQ(run.wallClock.spanMs, run.frameGpu.median);
  EXPECT_FALSE(run.deviceState.unavailable.empty());  // the fake device has no NVML device
  const nlohmann::json json = toJson(run);
  EXPECT_EQ(json.at("wall_clock").at("frames"), 6);
  EXPECT_TRUE(json.at("device_state").at("source").is_null());
  EXPECT_TRUE(json.at("passes").at(0).contains("detectable_relative"));
}

// A workload that can isolate passes: each alone costs less than its span (no queue sharing),
// and "Cull" and "Draw" form a chain with "Cull" first.
class IsolatingWorkload : public testing::FakeWorkload {
 public:
  render::FrameTiming renderIsolatedFrame() override {
    render::FrameTiming t;
    t.passes.push_back({"Cull", "compute", false, 0.05, 0.0});
    t.passes.push_back({"Draw <main>", "graphics", false, 0.5, 0.05});
    t.passes.push_back({"Debug", "graphics", true, 0.0, -1.0});
    ++isolated;
    return t;
  }
  std::vector<double> criticalPathShares(const std::vector<double>& costMs) const override {
    const double length = costMs[0] + costMs[1];
    return {costMs[0] / length, costMs[1] / length, 0.0};
  }
  int isolated = 0;
};

TEST(RunLoop, CalibrationGivesIsolatedCostsAndCriticalShares) {
  IsolatingWorkload workload;
  RunResult run = runBenchmark(workload, RunOptions{1, 4, kDefaultUnstableSpread, {}});
  calibrateIsolated(workload, run, 3);
  EXPECT_EQ(workload.isolated, 3);
  EXPECT_EQ(run.isolatedFrames, 3u);
  const PassRecord* cull = run.findPass("Cull");
  ASSERT_NE(cull, nullptr);
  EXPECT_EQ(cull->isolatedMs, (std::vector<double>{0.05, 0.05, 0.05}));
  EXPECT_NEAR(cull->criticalShare, 0.05 / 0.55, 1e-12);
  EXPECT_FALSE(run.findPass("Debug")->hasIsolated());
  // Budgets judge the isolated cost; the JSON carries both.
  EXPECT_EQ(run.medians().passCost, "isolated");
  EXPECT_DOUBLE_EQ(run.medians().passMs.at("Cull"), 0.05);
  const nlohmann::json json = toJson(run);
  EXPECT_DOUBLE_EQ(json.at("passes").at(0).at("isolated_ms").at("median").get<double>(), 0.05);
  EXPECT_EQ(json.at("isolation").at("frames"), 3);
}

TEST(RunLoop, NoCalibrationWhereTheWorkloadCannotIsolate) {
  testing::FakeWorkload workload;
  RunResult run = runBenchmark(workload, RunOptions{1, 4, kDefaultUnstableSpread, {}});
  calibrateIsolated(workload, run, 3);
  EXPECT_EQ(run.isolatedFrames, 0u);
  EXPECT_EQ(run.medians().passCost, "span");
  EXPECT_FALSE(run.passes.front().hasIsolated());
}

TEST(RunLoop, CameraPathFramesKeepTheirTimesAndSlowestFrames) {
  testing::FakeWorkload workload;
  workload.flyPath(0.5);
  RunOptions options;
  options.warmup = 1;
  options.frames = 6;
  RunResult run = runBenchmark(workload, options);
  summarizeRun(run);
  ASSERT_EQ(run.framePathTimeS.size(), 6u);
  EXPECT_DOUBLE_EQ(run.framePathTimeS.front(), 0.5);  // frame 1: the warm-up frame 0 was at 0 s
  EXPECT_DOUBLE_EQ(run.framePathTimeS.back(), 3.0);
  // Measured frames 1 and 3 are executions 2 and 4, the slowest; then the last, slower than the rest.
  EXPECT_EQ(run.slowestFrames(3), (std::vector<std::size_t>{1, 3, 5}));
  EXPECT_DOUBLE_EQ(run.frameGpu.max, 100.0);
  EXPECT_GT(run.frameGpu.p99, run.frameGpu.p95);
  const auto json = toJson(run);
  EXPECT_EQ(json["path"]["slowest"][0]["path_time_s"], 1.0);
  EXPECT_EQ(json["path"]["slowest"].size(), 3u);
  EXPECT_EQ(json["samples"]["path_time_s"].size(), 6u);
  EXPECT_TRUE(json["frame_gpu_ms"].contains("p99"));
  EXPECT_NE(markdownReport(run).find("`--set camera.time=1`"), std::string::npos);
}

TEST(RunLoop, StillCameraHasNoPathSection) {
  testing::FakeWorkload workload;
  RunOptions options;
  options.frames = 4;
  RunResult run = runBenchmark(workload, options);
  summarizeRun(run);
  EXPECT_TRUE(run.framePathTimeS.empty());
  EXPECT_TRUE(run.slowestFrames(3).empty());
  EXPECT_FALSE(toJson(run).contains("path"));
  EXPECT_EQ(markdownReport(run).find("Camera path"), std::string::npos);
}

TEST(RunLoop, CulledPassesHaveNoSamples) {
  testing::FakeWorkload workload;
  const RunResult run = runBenchmark(workload, RunOptions{1, 4, kDefaultUnstableSpread, {}});
  const PassRecord* debug = run.findPass("Debug");
  ASSERT_NE(debug, nullptr);
  EXPECT_TRUE(debug->culled);
  EXPECT_TRUE(debug->samplesMs.empty());
  EXPECT_EQ(run.medians().passMs.count("Debug"), 0u);
  EXPECT_EQ(run.medians().passMs.count("Cull"), 1u);
}

TEST(RunLoop, LateTimingsAreCollectedFromFinish) {
  testing::FakeWorkload workload(/*latency=*/2);
  RunOptions options;
  options.warmup = 2;
  options.frames = 4;
  const RunResult run = runBenchmark(workload, options);
  ASSERT_EQ(run.frameGpuMs.size(), 4u);
  EXPECT_DOUBLE_EQ(run.passes[0].samplesMs.front(), 2.1);  // frame 2 is the first measured one
  EXPECT_DOUBLE_EQ(run.passes[0].samplesMs.back(), 5.1);
}

TEST(RunLoop, MissingTimingsAreADeviceError) {
  testing::FakeWorkload workload(/*latency=*/1);
  workload.dropOneTimingOnFinish();
  EXPECT_THROW(runBenchmark(workload, RunOptions{1, 3, kDefaultUnstableSpread, {}}), DeviceError);
}

TEST(RunLoop, ReportsProgressForEveryFrameAndMeasuresOverhead) {
  testing::FakeWorkload workload;
  std::vector<uint32_t> seen;
  RunOptions options{2, 6, kDefaultUnstableSpread, [&](uint32_t done, uint32_t total) {
                       EXPECT_EQ(total, 8u);
                       seen.push_back(done);
                     }};
  const RunResult run = runBenchmark(workload, options);
  ASSERT_EQ(seen.size(), 8u);
  EXPECT_EQ(seen.back(), 8u);
  EXPECT_GE(run.overhead.loopWallMs, run.overhead.workloadCallsMs);
  EXPECT_GE(run.overhead.harnessMs, 0.0);
}

TEST(RunLoop, SpreadingSamplesAreFlaggedUnstable) {
  testing::FakeWorkload workload;  // pass times grow by 1 ms per frame: a huge spread for "Cull"
  const RunResult run = runBenchmark(workload, RunOptions{0, 10, kDefaultUnstableSpread, {}});
  EXPECT_TRUE(run.findPass("Cull")->unstable);
}

}  // namespace
}  // namespace fgb::harness

namespace fgb::harness {
namespace {

TEST(RunLoop, NonFiniteCountsGoToTheirPassesAndTheFirstBadOneIsNamed) {
  testing::FakeWorkload workload;
  workload.setNonFiniteCounts({{"Cull", 0, 0, 0}, {"Draw <main>", 3, 1, 2}, {"Debug", 5, 0, 0}});
  RunOptions options;
  options.warmup = 0;
  options.frames = 2;
  const RunResult run = runBenchmark(workload, options);
  EXPECT_TRUE(run.checkedFinite);
  ASSERT_NE(run.firstNonFinite(), nullptr);
  EXPECT_EQ(run.firstNonFinite()->pass, "Draw <main>");  // execution order, not the largest count
  const nlohmann::json json = toJson(run);
  EXPECT_EQ(json["check_finite"]["first_bad_pass"], "Draw <main>");
  EXPECT_EQ(json["check_finite"]["checked_passes"], 3);
  EXPECT_EQ(json["passes"][1]["non_finite"], (nlohmann::json{{"nan", 3}, {"inf", 1}, {"over_half_max", 2}}));
  EXPECT_EQ(json["passes"][0]["non_finite"]["nan"], 0);
  const std::string report = markdownReport(run);
  EXPECT_NE(report.find("First bad value produced by **Draw <main>** (NaN 3, Inf 1"), std::string::npos) << report;
}

TEST(RunLoop, WithoutCheckFiniteNoCountsAreReported) {
  testing::FakeWorkload workload;
  RunOptions options;
  options.warmup = 0;
  options.frames = 1;
  const RunResult run = runBenchmark(workload, options);
  EXPECT_FALSE(run.checkedFinite);
  EXPECT_EQ(run.firstNonFinite(), nullptr);
  const nlohmann::json json = toJson(run);
  EXPECT_FALSE(json["check_finite"]["enabled"].get<bool>());
  EXPECT_FALSE(json["passes"][0].contains("non_finite"));
  EXPECT_EQ(markdownReport(run).find("Non-finite"), std::string::npos);
}

TEST(Knobs, ParsesAssignmentsAndRejectsMalformedOnes) {
  const auto knobs = parseKnobs({"bloom=off", "exposure=0.6", "path=a=b"});
  EXPECT_EQ(knobs.at("bloom"), "off");
  EXPECT_EQ(knobs.at("path"), "a=b");
  EXPECT_THROW(parseKnobs({"novalue"}), InputError);
  EXPECT_THROW(parseKnobs({"=x"}), InputError);
}

}  // namespace
}  // namespace fgb::harness

namespace fgb::harness {
namespace {

// Async compute on: "Cull" (compute) runs inside "Draw" (graphics), 0.1 ms of overlap, a 1.0 ms
// frame. On one queue: Cull, a 0.1 ms gap, then Draw, a 1.2 ms frame.
class TwoQueueWorkload : public testing::FakeWorkload {
 public:
  TwoQueueWorkload() { constantTimes(); }
  uint32_t queuesUsed() const override { return async_ ? 2 : 1; }
  bool setAsyncCompute(bool on) override {
    async_ = on;
    ++switches;
    return true;
  }
  render::FrameTiming renderFrame() override {
    render::FrameTiming t = FakeWorkload::renderFrame();  // Cull [0, 0.1], Draw [0.1, 1.1]
    if (async_) {
      t.passes[0].gpuStartMs = 0.5;
      t.passes[1].gpuStartMs = 0.0;
      t.gpuFrameMs = 1.0;
    } else {
      t.passes[1].gpuStartMs = 0.2;
      t.gpuFrameMs = 1.2;
    }
    return t;
  }
  int switches = 0;

 private:
  bool async_ = true;
};

TEST(AsyncCompute, StatesWhatTheSecondQueueSavedAndHowLongTheQueuesOverlapped) {
  TwoQueueWorkload workload;
  RunResult run = runBenchmark(workload, RunOptions{1, 8, kDefaultUnstableSpread, {}});
  compareAsyncCompute(workload, run, 10);
  EXPECT_EQ(workload.switches, 2);  // to one queue and back
  EXPECT_EQ(workload.queuesUsed(), 2u);
  ASSERT_TRUE(run.asyncCompute.compared());
  EXPECT_EQ(run.asyncCompute.singleQueueMs.size(), 10u);  // the 2 warm-up frames dropped
  EXPECT_NEAR(run.asyncCompute.savedMs, 0.2, 1e-12);
  EXPECT_NEAR(run.asyncCompute.savedLowMs, 0.2, 1e-12);
  EXPECT_NEAR(run.asyncCompute.overlapMs, 0.1, 1e-12);
  EXPECT_NEAR(run.asyncCompute.idleGapsMs.front(), 0.1, 1e-12);
  const nlohmann::json json = toJson(run).at("async_compute");
  EXPECT_EQ(json.at("queues"), 2);
  EXPECT_NEAR(json.at("saved_ms").at("median").get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(json.at("single_queue_frame_ms").at("median").get<double>(), 1.2, 1e-12);
  EXPECT_NE(describeAsync(run.asyncCompute).find("async compute saved 0.2000 ms"), std::string::npos);
  EXPECT_NE(markdownReport(run).find("the queues overlapped 0.1000 ms per frame"), std::string::npos);
}

TEST(AsyncCompute, OneQueueOrACameraPathIsNotCompared) {
  testing::FakeWorkload oneQueue;
  RunResult run = runBenchmark(oneQueue, RunOptions{1, 4, kDefaultUnstableSpread, {}});
  compareAsyncCompute(oneQueue, run, 8);
  EXPECT_FALSE(run.asyncCompute.compared());
  EXPECT_NE(run.asyncCompute.skipped.find("one queue"), std::string::npos);
  EXPECT_TRUE(toJson(run).at("async_compute").contains("skipped"));
  EXPECT_EQ(markdownReport(run).find("Async compute:"), std::string::npos);

  TwoQueueWorkload path;
  path.flyPath(0.5);
  RunResult pathRun = runBenchmark(path, RunOptions{1, 4, kDefaultUnstableSpread, {}});
  compareAsyncCompute(path, pathRun, 8);
  EXPECT_EQ(path.switches, 0);
  EXPECT_NE(pathRun.asyncCompute.skipped.find("camera path"), std::string::npos);
}

TEST(AsyncCompute, OverlapCountsTimeWithTwoQueuesBusyAndGapsTimeWithNone) {
  const std::vector<PassInterval> passes = {{"graphics", 0.0, 1.0},
                                            {"graphics", 0.5, 2.0},  // one busy interval [0, 2] on graphics
                                            {"compute", 1.5, 3.0},   // overlaps graphics over [1.5, 2]
                                            {"transfer", 2.0, 2.5},  // touches graphics' end: overlaps compute only
                                            {"compute", 4.0, 5.0}};  // alone after a 1 ms gap
  EXPECT_NEAR(queueOverlapMs(passes), 0.5 + 0.5, 1e-12);
  EXPECT_NEAR(idleGapsMs(passes, 5.5), 1.0 + 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(queueOverlapMs({}), 0.0);
}

}  // namespace
}  // namespace fgb::harness
