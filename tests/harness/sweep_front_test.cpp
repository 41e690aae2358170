// The sweep's front (markFront): one front per view. Configurations that differ in a varied
// content axis render different images, each against its own reference, so a far view that is
// both cheaper and closer to its own reference must not "dominate" the near view.
#include <gtest/gtest.h>

#include <fgb/harness/sweep/sweep.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>
#include <string>
#include <vector>

namespace fgb::harness {
namespace {

// A configuration at `point` whose frames all take `ms` and whose LDR-FLIP mean is `error`.
ConfigurationOutcome measured(std::vector<std::pair<std::string, std::string>> point, double ms, double error) {
  ConfigurationOutcome c;
  for (const auto& [key, value] : point)
    c.configuration.label += (c.configuration.label.empty() ? "" : " ") + key + "=" + value;
  c.configuration.point = std::move(point);
  c.run.frameGpuMs.assign(32, ms);
  c.frameGpu.median = ms;
  c.display.flip = FlipStatistics{"ldr", error, error, error, error, error, 0.0, 0.0, 0};
  return c;
}

// camera.distance (content) x render.lod_error (an approximation), as issue 25's distance sweep.
SweepResult distanceSweep() {
  SweepResult r;
  r.axes = {{"camera.distance", {"1", "64"}}, {"render.lod_error", {"0", "1"}}};
  r.roles = {{"camera.distance", "content"}, {"render.lod_error", "approximation"}};
  r.configurations = {
      measured({{"camera.distance", "1"}, {"render.lod_error", "0"}}, 0.92, 0.020),
      measured({{"camera.distance", "1"}, {"render.lod_error", "1"}}, 0.95, 0.026),  // slower and worse
      measured({{"camera.distance", "64"}, {"render.lod_error", "0"}}, 0.45, 0.004),
      measured({{"camera.distance", "64"}, {"render.lod_error", "1"}}, 0.35, 0.006),
  };
  return r;
}

TEST(SweepFront, EachViewHasItsOwnFront) {
  SweepResult r = distanceSweep();
  EXPECT_EQ(viewKeys(r), std::vector<std::string>{"camera.distance"});
  EXPECT_EQ(viewOf(r, r.configurations[3]), "camera.distance=64");
  markFront(r);
  // The far view is cheaper and closer to its reference than anything of the near view, yet the
  // near view's best configuration stays on its own front, dominated by nothing.
  EXPECT_TRUE(r.configurations[0].onFront);
  EXPECT_TRUE(r.configurations[0].dominatedBy.empty());
  EXPECT_FALSE(r.configurations[1].onFront);
  EXPECT_EQ(r.configurations[1].dominatedBy, std::vector<std::size_t>{0});  // indices into the whole sweep
  EXPECT_TRUE(r.configurations[2].onFront);
  EXPECT_TRUE(r.configurations[3].onFront);  // faster, a little worse: a trade within its view
}

TEST(SweepFront, WithoutAContentAxisThereIsOneFront) {
  SweepResult r = distanceSweep();
  r.roles["camera.distance"] = "look";  // as if it only changed the look: one view
  EXPECT_TRUE(viewKeys(r).empty());
  markFront(r);
  EXPECT_FALSE(r.configurations[0].onFront);
  EXPECT_FALSE(r.configurations[1].onFront);
  EXPECT_TRUE(r.configurations[2].onFront);
  EXPECT_TRUE(r.configurations[3].onFront);
}

TEST(SweepFront, TheReportSaysTheFrontsArePerView) {
  SweepResult r = distanceSweep();
  markFront(r);
  const std::string markdown = sweepMarkdown(r);
  EXPECT_NE(markdown.find("each view has its own front"), std::string::npos) << markdown;
}

}  // namespace
}  // namespace fgb::harness
