#include <fgb/core/atomic_file.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/report/dart.hpp>
#include <fgb/harness/report/html_util.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/run/run_loop.hpp>

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
  EXPECT_THAT(html, Not(HasSubstr("<script")));  // only the golden flip view needs one
  EXPECT_THAT(html, Not(HasSubstr("src=")));      // no pictures given, none referenced
  EXPECT_THAT(html, Not(HasSubstr("<link")));
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::vector<uint8_t> bytes(std::string_view text) { return {text.begin(), text.end()}; }

TEST(Report, HtmlShowsTheFrameInlineAndWithAGoldenThreeImagesAndAFlipView) {
  const ReportImages frameOnly{bytes("frame-bytes"), {}, {}, 8, 4, {}, {}, {}};
  const std::string plain = htmlReport(fakeRun(), frameOnly);
  EXPECT_THAT(plain, HasSubstr(R"(id="frame" src="data:image/png;base64,)" + base64(bytes("frame-bytes")) + "\""));
  EXPECT_EQ(count(plain, "<img"), 1u);

  const ReportImages withGolden{bytes("frame-bytes"), bytes("reference-bytes"), bytes("heat-bytes"), 8, 4, {}, {}, {}};
  const std::string html = htmlReport(fakeRun(), withGolden);
  EXPECT_EQ(count(html, "<img"), 4u);  // reference, test, heat map, flip view
  EXPECT_EQ(count(html, "src=\"data:image/png;base64,"), 3u);  // each picture once: the flip view borrows them
  EXPECT_EQ(count(html, "src=\""), count(html, "src=\"data:"));  // nothing outside the file
  for (const char* id : {"golden-reference", "frame", "golden-heatmap", "flip-view", "flip-toggle"}) {
    EXPECT_THAT(html, HasSubstr("id=\"" + std::string(id) + "\"")) << id;
  }
  EXPECT_THAT(html, HasSubstr("<script>"));
}

TEST(Report, Base64MatchesRfc4648) {
  EXPECT_EQ(base64(bytes("")), "");
  EXPECT_EQ(base64(bytes("f")), "Zg==");
  EXPECT_EQ(base64(bytes("fo")), "Zm8=");
  EXPECT_EQ(base64(bytes("foo")), "Zm9v");
  EXPECT_EQ(base64(bytes("foobar")), "Zm9vYmFy");
  EXPECT_EQ(base64(std::vector<uint8_t>{0xff, 0x00, 0xfe}), "/wD+");
}

TEST(Report, TimelineDrawsEachPassFromItsBeginToItsEnd) {
  RunResult run = fakeRun();
  const std::string svg = queueTimelineSvg(run);
  EXPECT_THAT(svg, HasSubstr("begin/end timestamps"));
  EXPECT_EQ(count(svg, "class=\"span\""), 2u);  // Cull and Draw; Debug is culled
  // The frame of median GPU time (frames 1..4 have 3.1, 5.1, 7.1, 9.1 ms: the third) with its own times:
  // Draw <main> began at 0.1 + f = 3.1 ms and took 1 + f = 4 ms (f = 3, the frame's index with warm-up).
  EXPECT_THAT(svg, HasSubstr("Draw &lt;main&gt;: 3.1000 → 7.1000 ms"));
  EXPECT_THAT(svg, HasSubstr("queues overlap 0.0000 ms"));
  for (auto& p : run.passes) p.startMs.clear();
  EXPECT_THAT(queueTimelineSvg(run), HasSubstr("back to back"));
}

TEST(Report, TimelineShowsOverlapBetweenQueues) {
  RunResult run = fakeRun();
  for (auto& p : run.passes) std::fill(p.startMs.begin(), p.startMs.end(), 0.0);  // Cull and Draw both begin at 0
  const std::string svg = queueTimelineSvg(run);
  EXPECT_EQ(count(svg, "class=\"overlap\""), 1u);
  EXPECT_THAT(svg, HasSubstr("queues overlap 3.1000 ms"));  // Cull's 3.1 ms, all under Draw
}

TEST(Report, TimelineNamesPassesWithoutABeginInsteadOfGuessing) {
  RunResult run = fakeRun();
  run.passes[0].startMs.clear();  // Cull's queue gave no begin timestamp
  const std::string svg = queueTimelineSvg(run);
  EXPECT_THAT(svg, HasSubstr("the device gave no begin timestamp for: Cull"));
  EXPECT_EQ(count(svg, "class=\"span\""), 1u);
}

TEST(Report, TimelineNamesPassesThatRecordedNoGpuWork) {
  RunResult run = fakeRun();
  run.passes[0].startMs.clear();
  std::fill(run.passes[0].samplesMs.begin(), run.passes[0].samplesMs.end(), 0.0);  // a node that recorded nothing
  EXPECT_THAT(queueTimelineSvg(run), HasSubstr("recorded no GPU work: Cull"));
}

TEST(Report, SmallPassesStayReadable) {
  RunResult run = fakeRun();
  for (auto& s : run.passes[0].samplesMs) s = 0.001;  // Cull: far under 1% of the frame
  run.passes[0].gpu = summarize(run.passes[0].samplesMs);
  const std::string timeline = queueTimelineSvg(run);
  EXPECT_THAT(timeline, HasSubstr(">Cull</text>"));           // its own row, named
  EXPECT_THAT(timeline, HasSubstr("0.0010 ms (0.014%)"));     // with its time in words
  EXPECT_THAT(passBarsSvg(run), HasSubstr("log scale"));      // bars on a log axis
  EXPECT_THAT(passBarsSvg(fakeRun()), Not(HasSubstr("log scale")));
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
