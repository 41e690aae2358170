#include <fgb/core/error.hpp>
#include <fgb/core/atomic_file.hpp>
#include <fgb/harness/compare_runs.hpp>
#include <fgb/harness/json_io.hpp>

#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;

// Deterministic jittered samples around `center` (±1%).
std::vector<double> samplesAround(double center, int n, double phase) {
  std::vector<double> out;
  for (int i = 0; i < n; ++i) out.push_back(center * (1.0 + 0.01 * std::sin(i * 1.37 + phase)));
  return out;
}

LoadedTimings timings(std::map<std::string, double> centers, double phase) {
  LoadedTimings t;
  for (const auto& [name, center] : centers) {
    PassRecord p;
    p.name = name;
    p.samplesMs = samplesAround(center, 64, phase);
    p.gpu = summarize(p.samplesMs);
    t.passes.push_back(p);
  }
  return t;
}

const PassComparison& row(const RunsComparison& c, const std::string& pass) {
  for (const auto& r : c.rows) {
    if (r.pass == pass) return r;
  }
  throw std::runtime_error("no row " + pass);
}

TEST(CompareRuns, TwentyPercentSlowdownIsARegression) {
  const auto old = timings({{"Bloom", 0.4}, {"Mesh Render", 3.0}}, 0.0);
  const auto slower = timings({{"Bloom", 0.48}, {"Mesh Render", 3.0}}, 0.5);
  const RunsComparison c = compareRuns(old, slower);
  EXPECT_EQ(row(c, "Bloom").verdict, "slower");
  EXPECT_NEAR(row(c, "Bloom").deltaRelative, 0.2, 0.01);
  EXPECT_LT(row(c, "Bloom").test.pAGreater, 1e-6);
  EXPECT_EQ(row(c, "Mesh Render").verdict, "same");
  EXPECT_TRUE(c.anySlower());
  EXPECT_THAT(formatTable(c), HasSubstr("slower"));
}

TEST(CompareRuns, NoiseAloneIsNotARegression) {
  const RunsComparison c = compareRuns(timings({{"Bloom", 0.4}}, 0.0), timings({{"Bloom", 0.4}}, 1.1));
  EXPECT_EQ(row(c, "Bloom").verdict, "same");
  EXPECT_FALSE(c.anySlower());
}

TEST(CompareRuns, SignificantButTinyChangeIsBelowTheEffectThreshold) {
  // +2%: beyond the ±1% jitter, so significant, but under the 5% minimum effect.
  const RunsComparison c = compareRuns(timings({{"Bloom", 0.4}}, 0.0), timings({{"Bloom", 0.408}}, 0.0));
  EXPECT_LT(row(c, "Bloom").test.pAGreater, 0.01);
  EXPECT_EQ(row(c, "Bloom").verdict, "same");
  CompareRunsOptions strict;
  strict.minEffect = 0.01;
  strict.minAbsMs = 0.0;
  EXPECT_EQ(row(compareRuns(timings({{"Bloom", 0.4}}, 0.0), timings({{"Bloom", 0.408}}, 0.0), strict), "Bloom").verdict, "slower");
}

TEST(CompareRuns, SpeedupsAddedAndRemovedPassesAreNotRegressions) {
  const RunsComparison c = compareRuns(timings({{"Bloom", 0.4}, {"Old", 1.0}}, 0.0), timings({{"Bloom", 0.3}, {"New", 1.0}}, 0.0));
  EXPECT_EQ(row(c, "Bloom").verdict, "faster");
  EXPECT_EQ(row(c, "New").verdict, "added");
  EXPECT_EQ(row(c, "Old").verdict, "removed");
  EXPECT_FALSE(c.anySlower());
  EXPECT_FALSE(toJson(c)["regression"].get<bool>());
}

TEST(CompareRuns, LoadsTimingsJsonAndRejectsBadOnes) {
  testing::ScratchDir dir;
  nlohmann::json good{{"schema", 1}, {"scene", "s"},
                      {"passes", {{{"name", "Bloom"}, {"queue", "graphics"}, {"culled", false}, {"samples_ms", {0.4, 0.41, 0.39}}}}},
                      {"samples", {{"frame_gpu_ms", {1.0, 1.1, 0.9}}}}};
  writeFileAtomic(dir / "good.json", dumpJson(good));
  const LoadedTimings t = loadTimings(dir / "good.json");
  ASSERT_EQ(t.passes.size(), 1u);
  EXPECT_EQ(t.passes[0].samplesMs.size(), 3u);
  EXPECT_EQ(t.frameGpuMs.size(), 3u);

  nlohmann::json noSamples = good;
  noSamples["passes"][0].erase("samples_ms");
  writeFileAtomic(dir / "nosamples.json", dumpJson(noSamples));
  try {
    loadTimings(dir / "nosamples.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("passes[0].samples_ms"));
  }
  nlohmann::json wrongSchema = good;
  wrongSchema["schema"] = 7;
  writeFileAtomic(dir / "schema.json", dumpJson(wrongSchema));
  EXPECT_THROW(loadTimings(dir / "schema.json"), InputError);
  nlohmann::json badSample = good;
  badSample["passes"][0]["samples_ms"][1] = "x";
  writeFileAtomic(dir / "bad.json", dumpJson(badSample));
  EXPECT_THROW(loadTimings(dir / "bad.json"), InputError);
}

}  // namespace
}  // namespace fgb::harness
