#include <fgb/core/error.hpp>
#include <fgb/harness/results/budget.hpp>

#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;

const std::filesystem::path kThesisBudget =
    std::filesystem::path(FGBENCH_SOURCE_DIR) / "bench/budgets/thesis-sponza-gtx1660ti.json";

MeasuredMedians thesisNumbers() {
  MeasuredMedians m;
  m.passMs = {{"Clustered Light Cull", 0.9}, {"Particle Emit", 0.1}, {"Particle Update", 0.12},
              {"Particle Render", 0.12}, {"Mesh Frustum Cull", 0.005}, {"Mesh Render", 3.11},
              {"Bloom", 0.4}, {"Tone mapping", 0.07}};
  m.frameMs = 5.2;
  m.width = 1920;
  m.height = 1080;
  m.msaa = 8;
  return m;
}

TEST(Budget, ThesisTableIsEncoded) {
  const Budget b = loadBudget(kThesisBudget);
  ASSERT_EQ(b.passesMs.size(), 8u);
  EXPECT_EQ(b.passesMs[0].first, "Clustered Light Cull");
  EXPECT_DOUBLE_EQ(b.passesMs[0].second, 0.9);
  EXPECT_DOUBLE_EQ(b.passesMs[5].second, 3.11);
  ASSERT_TRUE(b.frameMs);
  EXPECT_DOUBLE_EQ(*b.frameMs, 5.2);
  EXPECT_EQ(b.width, 1920u);
  EXPECT_EQ(b.msaa, 8u);
  EXPECT_THAT(b.deviceName, HasSubstr("1660 Ti"));
}

TEST(Budget, TheThesisOwnNumbersPass) {
  const BudgetResult r = checkBudget(loadBudget(kThesisBudget), thesisNumbers());
  EXPECT_EQ(r.verdict, "pass");
  EXPECT_TRUE(r.failing().empty());
  EXPECT_TRUE(r.warnings.empty());
}

TEST(Budget, OverBudgetPassIsListedWithItsExcess) {
  MeasuredMedians m = thesisNumbers();
  m.passMs["Bloom"] = 0.5;  // budget 0.4, limit 0.44
  const BudgetResult r = checkBudget(loadBudget(kThesisBudget), m);
  EXPECT_EQ(r.verdict, "fail");
  ASSERT_EQ(r.failing().size(), 1u);
  const BudgetLine& line = *r.failing()[0];
  EXPECT_EQ(line.pass, "Bloom");
  EXPECT_EQ(line.status, "over");
  EXPECT_NEAR(line.overMs(), 0.1, 1e-12);
  EXPECT_NEAR(line.overPercent(), 25.0, 1e-9);
  EXPECT_EQ(toJson(r)["over"].size(), 1u);
  EXPECT_EQ(toJson(r)["over"][0]["pass"], "Bloom");
}

TEST(Budget, ToleranceDecidesTheBoundary) {
  MeasuredMedians m = thesisNumbers();
  m.passMs["Mesh Render"] = 3.11 * 1.09;
  EXPECT_EQ(checkBudget(loadBudget(kThesisBudget), m).verdict, "pass");  // file tolerance 10%
  EXPECT_EQ(checkBudget(loadBudget(kThesisBudget), m, 0.05).verdict, "fail");
}

TEST(Budget, MissingPassFailsAndConfigMismatchWarns) {
  MeasuredMedians m = thesisNumbers();
  m.passMs.erase("Particle Emit");
  m.width = 640;
  m.height = 360;
  const BudgetResult r = checkBudget(loadBudget(kThesisBudget), m);
  EXPECT_EQ(r.verdict, "fail");
  ASSERT_EQ(r.failing().size(), 1u);
  EXPECT_EQ(r.failing()[0]->status, "missing");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], HasSubstr("1920x1080"));
}

TEST(Budget, FrameOverBudgetFails) {
  MeasuredMedians m = thesisNumbers();
  m.frameMs = 6.0;
  const BudgetResult r = checkBudget(loadBudget(kThesisBudget), m);
  ASSERT_EQ(r.failing().size(), 1u);
  EXPECT_EQ(r.failing()[0]->pass, "(frame)");
}

TEST(Budget, BadFilesAreOneLineInputErrors) {
  testing::ScratchDir dir;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  const std::pair<std::string, std::string> cases[] = {
      {"syntax.json", "{\n  \"passes_ms\": {\"A\": 1.0,,}\n}"},
      {"nopasses.json", "{\"frame_ms\": 5}"},
      {"negative.json", "{\"passes_ms\": {\"A\": -1}}"},
      {"string.json", "{\"passes_ms\": {\"A\": \"fast\"}}"},
  };
  for (const auto& [name, text] : cases) {
    try {
      loadBudget(write(name, text));
      FAIL() << name;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(name));
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  try {
    loadBudget(dir / "syntax.json");
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("line 2"));
  }
  EXPECT_THROW(loadBudget(dir / "absent.json"), InputError);
}

}  // namespace
}  // namespace fgb::harness

namespace fgb::harness {
namespace {

TEST(Budget, APassSplitIntoPartsIsCheckedAgainstTheirSum) {
  MeasuredMedians m = thesisNumbers();
  m.passMs.erase("Bloom");
  m.passMs["Bloom Downsample 1"] = 0.2;
  m.passMs["Bloom Upsample 1"] = 0.3;  // 0.5 in total against 0.4 (+10%: 0.44)
  m.passMs["Bloomish"] = 5.0;          // not part of the group: no space after the name
  const BudgetResult r = checkBudget(loadBudget(kThesisBudget), m);
  ASSERT_EQ(r.failing().size(), 1u);
  const BudgetLine& line = *r.failing()[0];
  EXPECT_EQ(line.pass, "Bloom");
  EXPECT_EQ(line.summedPasses, 2u);
  EXPECT_NEAR(*line.measuredMs, 0.5, 1e-12);
  m.passMs["Bloom Upsample 1"] = 0.2;
  EXPECT_EQ(checkBudget(loadBudget(kThesisBudget), m).verdict, "pass");
}

}  // namespace
}  // namespace fgb::harness

namespace fgb::harness {
namespace {

TEST(Budget, FrameP99IsJudgedLikeTheMedian) {
  Budget budget;
  budget.passesMs = {{"Mesh Render", 3.0}};
  budget.frameP99Ms = 4.0;
  budget.tolerance = 0.0;
  MeasuredMedians measured;
  measured.passMs = {{"Mesh Render", 2.0}};
  measured.frameP99Ms = 4.5;  // the slow frames along a path go over
  const BudgetResult result = checkBudget(budget, measured);
  EXPECT_EQ(result.verdict, "fail");
  ASSERT_EQ(result.failing().size(), 1u);
  EXPECT_EQ(result.failing()[0]->pass, "(frame p99)");
  measured.frameP99Ms = 3.9;
  EXPECT_EQ(checkBudget(budget, measured).verdict, "pass");
}

}  // namespace
}  // namespace fgb::harness
