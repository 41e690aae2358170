// `fgbench stress SCENE --ladder KEY=V0,V1,...`: numerical stability of one knob against its
// baseline rung V0 (see fgb/harness/stress.hpp); stress.json/.md/.html into --out DIR; exit 1 when
// a rung fails, 2 on bad input.
#include <fmt/format.h>

#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/results/golden.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/harness/stress/stress.hpp>
#include <fgb/renderer/workload.hpp>
#include <fgb/scene/load.hpp>
#include <iostream>

#include "verb.hpp"

namespace fgb::app {
namespace {

struct StressOptions {
  CommonOptions common;
  std::string scene;
  std::string ladder;
  std::string out;
  double maxFlip = -1.0;        // < 0: the ladder's default
  double maxPixelShare = -1.0;  // percent
  double maxAbs = -1.0;
  bool allowNonFinite = false;
  bool failOverHalfMax = false;
};

// The exposure light-scale compensates: the scene's (after --set), or auto.
harness::LadderContext ladderContext(const StressOptions& o) {
  if (o.ladder.rfind("light-scale", 0) != 0) return {};
  scene::LoadOptions load;
  load.knobs = checkedKnobs(o.common.sets);
  const scene::LoadedScene loaded = scene::loadScene(o.scene, load);
  return {loaded.scene.post.exposure, loaded.scene.post.autoExposure};
}

harness::StressPlan makePlan(const StressOptions& o) {
  harness::StressPlan plan;
  plan.scene = o.scene;
  plan.base = workloadConfig(o.scene, o.common, checkedKnobs(o.common.sets));
  plan.ladder = harness::parseLadder(o.ladder, ladderContext(o));
  harness::StressThresholds& t = plan.ladder.thresholds;
  if (o.maxFlip >= 0) t.flipMean = o.maxFlip;
  if (o.maxPixelShare >= 0) t.pixelShare = o.maxPixelShare / 100.0;
  if (o.maxAbs >= 0) t.maxAbs = o.maxAbs;
  t.nonFinite = !o.allowNonFinite;
  t.overHalfMax = o.failOverHalfMax;
  // Every rung's knobs are checked before anything renders (exit 2 with one line).
  for (const auto& rung : plan.ladder.rungs) {
    for (const auto& [key, value] : rung.knobs) {
      if (plan.base.knobs.count(key)) throw InputError("--ladder " + o.ladder + ": " + key + " is also fixed by --set");
      knobRegistry().check(key, value);
    }
  }
  return plan;
}

int stressVerb(StressOptions o) {
  const harness::StressPlan plan = makePlan(o);
  if (o.out.empty()) o.out = "out/" + harness::sceneName(o.scene) + "-stress-" + plan.ladder.name;
  const bool chatty = !o.common.quiet && !o.common.json;
  const auto progress = [&](std::size_t rung, std::size_t rungs, const std::string& value) {
    if (chatty) std::cerr << fmt::format("stress: rung {}/{}: {}\n", rung + 1, rungs, value);
  };
  harness::StressResult result = harness::runStress(render::openWorkload, plan, progress);
  result.toolVersion = FGBENCH_VERSION;
  harness::writeStressOutputs(o.out, result);

  if (o.common.json) {
    std::cout << harness::dumpJson(harness::toJson(result));
  } else if (!o.common.quiet) {
    std::cout << harness::stressMarkdown(result) << "\n  results in " << o.out
              << " (stress.html, stress.json, stress.md)\n";
  }
  if (result.firstFailure())
    throw CheckFailed(fmt::format("stress {} --ladder {}: {}", o.scene, plan.ladder.name, result.summary()));
  return kExitOk;
}

static VerbRegistrar reg(35, [](CLI::App& app) {
  auto o = std::make_shared<StressOptions>();
  CLI::App* sub = app.add_subcommand(
      "stress", "Numerical stability: render one knob at a ladder of values against its baseline rung (stress.html)");
  sub->add_option("scene", o->scene, "Scene file (scenes/*.json)")->required();
  addCommonOptions(*sub, o->common);
  sub->add_option("--ladder", o->ladder,
                  "NAME (offset, near, light-scale, radiance, fov, resolution), NAME=V0,V1,... or KEY=V0,V1,... "
                  "(any --set knob, or size=WxH,...); V0 is the baseline")
      ->required();
  sub->add_option("--out", o->out, "Output directory (default: out/<scene>-stress-<ladder>)");
  sub->add_option("--max-flip", o->maxFlip,
                  "Fail a rung whose FLIP mean against the baseline exceeds the baseline's noise by more than this "
                  "(default: offset 0.005, near 0.002, others 0.01)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_option("--max-pixel-share", o->maxPixelShare,
                  "Fail a rung with more than this percentage of pixels off by > 2/255 beyond the noise (default 5)")
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--max-abs", o->maxAbs, "Fail a rung whose max abs display error exceeds this (default: off)")
      ->check(CLI::Range(0.0, 1.0));
  sub->add_flag("--allow-non-finite", o->allowNonFinite, "Do not fail rungs whose passes write NaN or Inf");
  sub->add_flag("--fail-over-half-max", o->failOverHalfMax,
                "Also fail rungs whose passes write values above half of R16F's maximum (32752; else reported)");
  return Verb{sub, [o] { return stressVerb(*o); }};
});

}  // namespace
}  // namespace fgb::app
