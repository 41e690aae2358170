#include <gtest/gtest.h>

#include <fgb/core/error.hpp>
#include <fgb/harness/run/render_path.hpp>
#include <fgb/harness/run/run_loop.hpp>

#include "fake_workload.hpp"

namespace fgb::harness {
namespace {

// Opens fake workloads and remembers what it was asked for.
struct FakeOpener {
  std::vector<render::WorkloadConfig> opened;
  bool constant = false;
  std::size_t latency = 0;
  WorkloadOpener opener() {
    return [this](const render::WorkloadConfig& config) {
      opened.push_back(config);
      auto w = std::make_unique<testing::FakeWorkload>(latency);
      if (constant) w->constantTimes();
      return w;
    };
  }
};

RenderRequest request(uint32_t warmup, uint32_t frames) {
  RenderRequest r;
  r.workload.scenePath = "builtin:fake";
  r.workload.msaa = 4;
  r.workload.knobs = {{"bloom.mips", "3"}};
  r.warmup = warmup;
  r.frames = frames;
  return r;
}

TEST(RenderPath, FixedFramesMatchTheRunLoop) {
  FakeOpener open;
  open.latency = 2;
  RenderRequest r = request(3, 5);
  r.graphDumps = true;
  std::vector<std::pair<uint32_t, uint32_t>> progress;
  r.progress = [&](uint32_t done, uint32_t total) { progress.emplace_back(done, total); };
  const RunArtifacts a = renderConfiguration(open.opener(), r);

  testing::FakeWorkload direct(2);
  const RunResult expected = runBenchmark(direct, RunOptions{3, 5, kDefaultUnstableSpread, {}});
  ASSERT_EQ(open.opened.size(), 1u);
  EXPECT_EQ(open.opened[0].knobs, r.workload.knobs);
  EXPECT_EQ(a.run.frameGpuMs, expected.frameGpuMs);
  ASSERT_EQ(a.run.passes.size(), expected.passes.size());
  EXPECT_EQ(a.run.passes[0].samplesMs, expected.passes[0].samplesMs);
  EXPECT_EQ(progress.size(), 8u);
  EXPECT_EQ(progress.back(), (std::pair<uint32_t, uint32_t>{8, 8}));
  // Config: size from the images, MSAA as asked (the fake reports none), frames and knobs.
  EXPECT_EQ(a.run.config.width, 8u);
  EXPECT_EQ(a.run.config.height, 4u);
  EXPECT_EQ(a.run.config.msaa, 4u);
  EXPECT_EQ(a.run.config.frames, 5u);
  EXPECT_EQ(a.run.config.warmup, 3u);
  EXPECT_EQ(a.run.config.knobs, r.workload.knobs);
  EXPECT_EQ(a.run.scene, "builtin:fake");
  EXPECT_FLOAT_EQ(a.images.hdr.rgba[0], 2.0f);
  EXPECT_FLOAT_EQ(a.images.display.rgba[0], 0.5f);
  EXPECT_EQ(a.graphBrief, "digraph brief {}");
  EXPECT_GE(a.run.overhead.openMs, 0.0);
}

TEST(RenderPath, UntilStableStopsAtTheCapWhenTimesKeepMoving) {
  FakeOpener open;  // frame times grow with every frame: never stable
  RenderRequest r = request(2, 40);
  r.untilStable = StabilityRule{0.02, 16, 16};
  const RunArtifacts a = renderConfiguration(open.opener(), r);
  EXPECT_EQ(a.run.frameGpuMs.size(), 40u);  // 16 + 16 + 8
  EXPECT_FALSE(isStable(a.run, *r.untilStable));
  // Frames 2..41 measured, in order, across three measuring calls.
  EXPECT_DOUBLE_EQ(a.run.passes[0].samplesMs.front(), 2.1);
  EXPECT_DOUBLE_EQ(a.run.passes[0].samplesMs.back(), 41.1);
}

TEST(RenderPath, UntilStableStopsEarlyOnSteadyTimes) {
  FakeOpener open;
  open.constant = true;
  RenderRequest r = request(2, 200);
  r.untilStable = StabilityRule{0.02, 24, 16};
  const RunArtifacts a = renderConfiguration(open.opener(), r);
  EXPECT_EQ(a.run.frameGpuMs.size(), 24u);  // the first batch is max(minFrames, batch)
  EXPECT_TRUE(isStable(a.run, *r.untilStable));
}

TEST(RenderPath, RoundsAppendAlignedColumns) {
  FakeOpener open;
  ConfigurationRenderer renderer(open.opener(), request(0, 0).workload);
  renderer.warmUp(2);
  renderer.measure(3);
  renderer.measure(4, /*rewarm=*/1);
  const RunResult& run = renderer.result();
  ASSERT_EQ(run.frameGpuMs.size(), 7u);
  // Frames 2, 3, 4 then (5 dropped) 6, 7, 8, 9.
  EXPECT_EQ(run.passes[0].samplesMs, (std::vector<double>{2.1, 3.1, 4.1, 6.1, 7.1, 8.1, 9.1}));
  EXPECT_EQ(run.passes[1].startMs.size(), 7u);
  EXPECT_TRUE(run.findPass("Debug")->culled);
  EXPECT_TRUE(run.findPass("Debug")->samplesMs.empty());
  EXPECT_EQ(run.frameGpu.n, 7u);
  EXPECT_DOUBLE_EQ(run.passes[0].gpu.median, 6.1);
}

TEST(RenderPath, AppendingKeepsPassesSeenInOnlyOneRound) {
  RunResult total, round;
  total.frameGpuMs = {1, 1};
  total.frameCpuMs = {1, 1};
  total.passes.push_back(passRecord("A", "graphics", false, {1, 1}));
  total.passes.push_back(passRecord("C", "graphics", true));
  round.frameGpuMs = {2};
  round.frameCpuMs = {2};
  round.passes.push_back(passRecord("B", "compute", false, {5}));
  round.passes.push_back(passRecord("C", "graphics", false, {7}));
  appendMeasurements(total, round);
  ASSERT_EQ(total.passes.size(), 3u);
  EXPECT_EQ(total.findPass("A")->samplesMs, (std::vector<double>{1, 1, 0}));
  EXPECT_EQ(total.findPass("B")->samplesMs, (std::vector<double>{0, 0, 5}));
  EXPECT_FALSE(total.findPass("C")->culled);  // ran in the second round
  EXPECT_EQ(total.findPass("C")->samplesMs, (std::vector<double>{0, 0, 7}));
  EXPECT_EQ(total.frameGpu.n, 3u);
}

}  // namespace
}  // namespace fgb::harness
