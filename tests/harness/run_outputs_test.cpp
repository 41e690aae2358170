#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/run/run_loop.hpp>
#include <fgb/harness/run/run_outputs.hpp>

#include "fake_workload.hpp"
#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;

RunArtifacts fakeArtifacts() {
  testing::FakeWorkload workload;
  RunArtifacts a;
  a.run = runBenchmark(workload, RunOptions{1, 3, kDefaultUnstableSpread, {}});
  a.run.scene = "builtin:proof";
  a.images.hdr = fromRendered(workload.readHdr());
  a.images.display = fromRendered(workload.readDisplay());
  // A gradient so FLIP has structure to compare.
  for (std::size_t i = 0; i < a.images.display.rgba.size(); ++i) a.images.display.rgba[i] = static_cast<float>(i % 37) / 37.0f;
  a.graphBrief = workload.graphviz(render::GraphDetail::Brief);
  a.graphFull = workload.graphviz(render::GraphDetail::Full);
  return a;
}

// A golden made from the artifacts' own images (as bless writes it).
Golden makeGolden(const std::filesystem::path& dir, const RenderedImages& images) {
  writePng(dir / "default.png", images.display);
  writeExr(dir / "default.exr", images.hdr);
  const nlohmann::json doc{{"schema", 1},
                           {"images", {{"display", "default.png"}, {"hdr", "default.exr"}}},
                           {"thresholds", {{"display", toJson(thresholdsFromNoise(std::nullopt, false))},
                                           {"hdr", toJson(thresholdsFromNoise(std::nullopt, true))}}}};
  writeFileAtomic(dir / "default.json", dumpJson(doc));
  return loadGolden(dir);
}

TEST(RunOutputs, WritesEveryContractFile) {
  testing::ScratchDir dir;
  writeRunOutputs(dir / "out/nested", fakeArtifacts());
  for (const char* name : {"frame.exr", "frame.png", "timings.json", "timings.csv", "graph.dot", "graph-full.dot",
                           "report.md", "report.html"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out/nested" / name)) << name;
  }
  EXPECT_EQ(readImage(dir / "out/nested/frame.exr").width, 8u);
  for (const auto& entry : std::filesystem::directory_iterator(dir / "out/nested")) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::Not(HasSubstr(".tmp."))) << "no temporaries left";
  }
}

TEST(RunOutputs, GoldenOfTheSameRenderPasses) {
  testing::ScratchDir dir;
  const RunArtifacts a = fakeArtifacts();
  const GoldenResult r = checkGolden(makeGolden(dir.path(), a.images), a.images, dir / "diff");
  EXPECT_EQ(r.verdict, "pass");
  ASSERT_EQ(r.images.size(), 2u);
  EXPECT_EQ(r.images[0].metrics.rmse, 0.0);  // bit-exact: same quantisation as the files
  EXPECT_EQ(r.images[1].metrics.rmse, 0.0);
  EXPECT_TRUE(r.diffImage.empty());
}

TEST(RunOutputs, ChangedRenderFailsAndWritesTheHeatMap) {
  testing::ScratchDir dir;
  const RunArtifacts a = fakeArtifacts();
  const Golden golden = makeGolden(dir.path(), a.images);
  RenderedImages changed = a.images;
  for (float& v : changed.display.rgba) v = 1.0f - v;
  const GoldenResult r = checkGolden(golden, changed, dir / "diff");
  EXPECT_EQ(r.verdict, "fail");
  EXPECT_FALSE(r.images[0].failures.empty());
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "diff/golden-diff.png"));
  EXPECT_EQ(r.diffImage, (dir / "diff/golden-diff.png").string());
}

TEST(RunOutputs, NaNInTheRenderAlwaysFails) {
  testing::ScratchDir dir;
  const RunArtifacts a = fakeArtifacts();
  const Golden golden = makeGolden(dir.path(), a.images);
  RenderedImages broken = a.images;
  broken.hdr.rgba[5] = std::numeric_limits<float>::quiet_NaN();
  const GoldenResult r = checkGolden(golden, broken, dir / "diff");
  EXPECT_EQ(r.verdict, "fail");
  EXPECT_THAT(r.images[1].failures.at(0), HasSubstr("NaN"));
}

TEST(RunOutputs, SizeMismatchIsInputErrorAndGoldenUntouched) {
  testing::ScratchDir dir;
  const RunArtifacts a = fakeArtifacts();
  const Golden golden = makeGolden(dir.path(), a.images);
  const auto before = std::filesystem::last_write_time(dir / "default.png");
  RenderedImages other = a.images;
  other.display = makeImage(4, 4, Encoding::Linear);
  try {
    checkGolden(golden, other, dir / "diff");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("default.png"));
    EXPECT_THAT(e.what(), HasSubstr("8x4"));
  }
  EXPECT_EQ(std::filesystem::last_write_time(dir / "default.png"), before);
}

TEST(RunOutputs, SceneHashIsStableAndContentBased) {
  testing::ScratchDir dir;
  writeFileAtomic(dir / "a.json", std::string_view("{\"x\": 1}"));
  writeFileAtomic(dir / "b.json", std::string_view("{\"x\": 2}"));
  EXPECT_EQ(sceneHash((dir / "a.json").string()), sceneHash((dir / "a.json").string()));
  EXPECT_NE(sceneHash((dir / "a.json").string()), sceneHash((dir / "b.json").string()));
  EXPECT_THAT(sceneHash("builtin:proof"), HasSubstr("fnv1a64:"));
}

}  // namespace
}  // namespace fgb::harness
