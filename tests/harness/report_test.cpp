#include <fgb/core/atomic_file.hpp>
#include <fgb/harness/dart.hpp>
#include <fgb/harness/json_io.hpp>
#include <fgb/harness/report.hpp>
#include <fgb/harness/run_loop.hpp>

#include "fake_workload.hpp"
#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

RunResult fakeRun() {
  testing::FakeWorkload workload;
  RunResult run = runBenchmark(workload, RunOptions{1, 4, kDefaultUnstableSpread, {}});
  run.scene = "builtin:proof";
  run.toolVersion = "0.1.0";
  run.config = {8, 4, 1, 4, 1, {{"bloom", "on"}}};
  Budget budget;
  budget.file = "b.json";
  budget.passesMs = {{"Cull", 1.0}, {"Draw <main>", 100.0}};
  run.budget = checkBudget(budget, run.medians());
  return run;
}

TEST(Report, TimingsJsonFollowsTheContract) {
  const nlohmann::json j = toJson(fakeRun());
  for (const char* key : {"schema", "tool_version", "scene", "scene_hash", "device", "config", "stats", "passes",
                          "frame_gpu_ms", "frame_cpu_ms", "budget", "golden"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["schema"], 1);
  for (const char* key : {"name", "driver", "type", "timestamp_period_ns"}) EXPECT_TRUE(j["device"].contains(key)) << key;
  for (const char* key : {"width", "height", "msaa", "frames", "warmup", "knobs"}) EXPECT_TRUE(j["config"].contains(key)) << key;
  const auto& pass = j["passes"][0];
  for (const char* key : {"name", "queue", "culled", "gpu_ms"}) EXPECT_TRUE(pass.contains(key)) << key;
  for (const char* key : {"median", "p5", "p95", "mean", "min", "max", "n"}) EXPECT_TRUE(pass["gpu_ms"].contains(key)) << key;
  EXPECT_EQ(j["budget"]["verdict"], "fail");  // Cull's median 2.1 ms > 1.1 ms
  EXPECT_EQ(j["budget"]["over"][0]["pass"], "Cull");
  EXPECT_EQ(j["golden"]["verdict"], "none");
}

TEST(Report, TimingsJsonRoundTripsThroughLoadTimings) {
  testing::ScratchDir dir;
  const RunResult run = fakeRun();
  writeFileAtomic(dir / "timings.json", dumpJson(toJson(run)));
  const LoadedTimings loaded = loadTimings(dir / "timings.json");
  ASSERT_EQ(loaded.passes.size(), run.passes.size());
  EXPECT_EQ(loaded.passes[1].samplesMs, run.passes[1].samplesMs);
  EXPECT_EQ(loaded.frameGpuMs, run.frameGpuMs);
}

TEST(Report, CsvHasOneRowPerPassPerFrame) {
  const std::string csv = toCsv(fakeRun());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 * 3);
  EXPECT_THAT(csv, HasSubstr("frame,pass,queue,culled,gpu_ms"));
}

TEST(Report, MarkdownNamesPassesBudgetAndHostClock) {
  const std::string md = markdownReport(fakeRun());
  EXPECT_THAT(md, HasSubstr("Draw <main>"));
  EXPECT_THAT(md, HasSubstr("over by"));
  EXPECT_THAT(md, HasSubstr("host clock"));
  EXPECT_THAT(md, HasSubstr("culled"));
}

TEST(Report, HtmlIsSelfContainedWithThreeEscapedCharts) {
  const std::string html = htmlReport(fakeRun());
  std::size_t svgs = 0;
  for (std::size_t at = html.find("<svg"); at != std::string::npos; at = html.find("<svg", at + 1)) ++svgs;
  EXPECT_EQ(svgs, 3u);
  EXPECT_THAT(html, HasSubstr("Draw &lt;main&gt;"));
  EXPECT_THAT(html, Not(HasSubstr("Draw <main>")));
  EXPECT_THAT(html, Not(HasSubstr("<script")));
  EXPECT_THAT(html, Not(HasSubstr("src=")));  // no external resources
  EXPECT_THAT(html, Not(HasSubstr("<link")));
}

TEST(Report, TimelineUsesReportedStartTimes) {
  RunResult run = fakeRun();
  EXPECT_THAT(queueTimelineSvg(run), HasSubstr("from GPU timestamps"));
  for (auto& p : run.passes) p.startMs.clear();
  EXPECT_THAT(queueTimelineSvg(run), HasSubstr("back to back"));
}

TEST(Report, TimelineNamesBoxesTooNarrowForTheirLabelBesideThem) {
  RunResult run = fakeRun();
  run.passes[0].gpu.median = 0.001;  // Cull: a sliver in its lane
  EXPECT_THAT(queueTimelineSvg(run), HasSubstr(R"(fill="#222" font-size="10" text-anchor="start">Cull</text>)"));
}

TEST(Report, HtmlLinksTheHeatMapOfEachFailingGoldenImage) {
  RunResult run = fakeRun();
  GoldenResult golden;
  golden.file = "golden/x/lavapipe/default.json";
  golden.verdict = "fail";
  golden.images.push_back({"display", {}, {}});
  golden.images.push_back({"hdr", {}, {"rmse 0.5 > 0.02"}});
  run.golden = golden;
  const std::string html = htmlReport(run);
  EXPECT_THAT(html, HasSubstr(R"(<a href="golden-diff-hdr.png">)"));
  EXPECT_THAT(html, Not(HasSubstr(R"(<a href="golden-diff.png">)")));  // the display image passed
  EXPECT_THAT(html, HasSubstr(R"(<a href="frame.png">)"));
}

TEST(Report, DartMeasurementsForCdash) {
  const std::string dart = dartMeasurements(fakeRun());
  EXPECT_THAT(dart, HasSubstr(R"(<DartMeasurement name="gpu_ms Cull" type="numeric/double">)"));
  EXPECT_THAT(dart, HasSubstr("frame_gpu_ms"));
  EXPECT_THAT(dart, Not(HasSubstr("Debug")));  // culled
}

}  // namespace
}  // namespace fgb::harness
