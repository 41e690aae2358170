// `fgbench sweep SCENE --vary KEY=V1,V2 [--vary ...] [--sweep FILE]`: run time against error over
// the full grid of the varied keys, each configuration compared with a supersampled reference;
// writes sweep.json/.csv/.md/.html into --out DIR and prints a table marking the Pareto front.
#include <fmt/format.h>

#include <algorithm>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/base/progress.hpp>
#include <fgb/harness/results/golden.hpp>
#include <fgb/harness/run/run_loop.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/harness/sweep/sweep.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>
#include <fgb/renderer/workload.hpp>
#include <fgb/scene/scene_file.hpp>
#include <iostream>

#include "verb.hpp"

namespace fgb::app {
namespace {

struct SweepOptions {
  CommonOptions common;
  std::string scene;
  std::vector<std::string> vary;
  std::string sweepFile;
  std::string out;
  bool untilStable = false;
  double stableWithin = 3.0;  // percent
  uint32_t maxFrames = 128;
  uint32_t roundFrames = 16;
  double maxMinutes = 0.0;
  uint64_t seed = 1;
  uint32_t referenceSsaa = 4;
  std::string shard;  // "K/N"
  uint32_t pathTimes = 4;  // along a camera path: judge error at this many path times (0: frame 2 only)
};

// The path times a sweep judges error at: spread over the scene file's camera path, unless the
// scene holds still (no path, camera.path=none, or camera.time fixed or varied) or K is 0.
std::vector<double> sweepPathTimes(const SweepOptions& o, const std::map<std::string, std::string>& knobs,
                                   const std::vector<harness::SweepAxis>& axes) {
  if (o.pathTimes == 0 || o.scene.starts_with("builtin:")) return {};
  for (const char* key : {"camera.path", "camera.time"}) {
    if (knobs.count(key)) return {};
    for (const auto& axis : axes)
      if (axis.key == key) return {};
  }
  const scene::SceneDescription description = scene::parseSceneFile(o.scene);
  const nlohmann::json& path =
      description.camera.is_object() ? description.camera.value("path", nlohmann::json()) : nlohmann::json();
  if (!path.is_array() || path.empty()) return {};
  return harness::spreadPathTimes(path.back().at("time").get<double>(), o.pathTimes);
}

// Axes from the sweep file, then --vary (a --vary of a key the file also varies replaces it).
std::vector<harness::SweepAxis> gatherAxes(const SweepOptions& o, const harness::SweepFile* file) {
  std::vector<harness::SweepAxis> axes;
  if (file) axes = file->axes;
  for (const auto& text : o.vary) {
    harness::SweepAxis axis = harness::parseVary(text);
    auto same = std::find_if(axes.begin(), axes.end(), [&](const auto& a) { return a.key == axis.key; });
    if (same != axes.end() && file && same - axes.begin() < static_cast<std::ptrdiff_t>(file->axes.size())) {
      *same = std::move(axis);
    } else {
      axes.push_back(std::move(axis));  // a key varied twice on the command line: expandGrid says so
    }
  }
  return axes;
}

// Every value of a knob axis against the knob registry, before anything opens: exit 2 naming it.
void checkAxisKnob(const harness::SweepAxis& axis) {
  if (!harness::isKnobAxis(axis.key)) return;
  for (const auto& value : axis.values) {
    try {
      knobRegistry().check(axis.key, value);
    } catch (const InputError& e) {
      const std::string message = e.what();
      throw InputError(message.starts_with("--set ") ? "--vary " + message.substr(6) : message);
    }
  }
}

harness::SweepPlan makePlan(const CLI::App& command, SweepOptions& o, std::vector<harness::SweepAxis>& axes,
                            std::optional<harness::ShardInfo>& shardInfo) {
  std::optional<harness::SweepFile> file;
  if (!o.sweepFile.empty()) file = harness::loadSweepFile(o.sweepFile);
  auto knobs = file ? file->knobs : std::map<std::string, std::string>{};
  for (const auto& [k, v] : harness::parseKnobs(o.common.sets)) knobs[k] = v;  // --set wins
  if (file && !command.count("--width") && file->width) o.common.width = file->width;
  if (file && !command.count("--height") && file->height) o.common.height = file->height;
  axes = gatherAxes(o, file ? &*file : nullptr);
  for (const auto& axis : axes) {
    checkAxisKnob(axis);
    if (knobs.count(axis.key))
      throw InputError("--vary " + axis.key + ": also fixed by --set " + axis.key + "=" + knobs[axis.key]);
    if (axis.key == "msaa" && command.count("--msaa")) throw InputError("--vary msaa: also fixed by --msaa");
  }

  harness::SweepPlan plan;
  plan.scene = o.scene;
  plan.configurations = harness::expandGrid(workloadConfig(o.scene, o.common, knobs), axes);
  // A configuration supersampled beyond its reference would be judged against a coarser image.
  for (const auto& c : plan.configurations) {
    const auto ssaa = c.workload.knobs.find("render.ssaa");
    if (ssaa != c.workload.knobs.end() && std::stoul(ssaa->second) > o.referenceSsaa)
      throw InputError(fmt::format("render.ssaa={}: above the reference's SSAA {} (raise --reference-ssaa)",
                                   ssaa->second, o.referenceSsaa));
  }
  plan.referenceRules.knobs = &knobRegistry();
  plan.referenceRules.ssaa = o.referenceSsaa;
  plan.referenceRules.baseKnobs = knobs;
  if (!o.shard.empty()) {
    const harness::ShardSpec spec = harness::parseShard(o.shard);
    harness::ShardInfo shard{spec.index, spec.count, plan.configurations.size(),
                             harness::shardConfigurations(plan.configurations, plan.referenceRules, spec)};
    std::vector<harness::SweepConfiguration> mine;
    for (std::size_t i : shard.gridIndices) mine.push_back(plan.configurations[i]);
    plan.configurations = std::move(mine);
    shardInfo = std::move(shard);
  }
  plan.warmup = o.common.warmup;
  plan.frames = o.common.frames;
  plan.stableFrameCap = o.maxFrames;
  const harness::StabilityRule rule{o.stableWithin / 100.0, 16, o.roundFrames};
  if (o.untilStable) plan.untilStable = rule;
  plan.cpuStabilityRule = rule;
  // --until-stable is the default on CPU devices unless a fixed --frames was asked for.
  plan.untilStableOnCpu = !command.count("--frames");
  // On lavapipe: no frames beyond what the statistics need (SweepPlan::trimOnCpu).
  plan.trimOnCpu = true;
  plan.trimWarmupOnCpu = !command.count("--warmup");
  plan.roundFrames = o.roundFrames;
  plan.maxMinutes = o.maxMinutes;
  plan.seed = o.seed;
  plan.pathTimes = sweepPathTimes(o, knobs, axes);
  return plan;
}

int sweepVerb(const CLI::App& command, SweepOptions o) {
  std::vector<harness::SweepAxis> axes;
  std::optional<harness::ShardInfo> shard;
  harness::SweepPlan plan = makePlan(command, o, axes, shard);
  if (o.out.empty()) o.out = "out/" + harness::sceneName(o.scene) + "-sweep";
  const bool chatty = !o.common.quiet && !o.common.json;

  harness::ProgressBar bar(std::cerr, "measuring", chatty && harness::ProgressBar::stderrIsTerminal());
  harness::SweepProgress progress;
  bool opened = false;  // the first phase is said once every configuration opened
  progress.phase = [&](const std::string& phase) {
    if (!chatty) return;
    if (!opened)
      std::cerr << fmt::format(
          "sweep: {} configuration(s) of {} opened{}\n", plan.configurations.size(), o.scene,
          shard ? fmt::format(" (shard {}/{} of a grid of {})", shard->index, shard->count, shard->gridSize) : "");
    opened = true;
    std::cerr << "sweep: " << phase << "\n";
  };
  progress.frames = [&](uint32_t done, uint32_t total) { bar.update(done, total); };

  harness::SweepResult result = harness::runSweep(render::openWorkload, plan, progress);
  bar.finish();
  result.toolVersion = FGBENCH_VERSION;
  result.axes = axes;
  result.shard = shard;
  harness::writeSweepOutputs(o.out, result);
  if (chatty) std::cerr << harness::sweepWallSummary(result);

  if (o.common.json) {
    std::cout << harness::dumpJson(harness::sweepJson(result));
  } else if (!o.common.quiet) {
    std::cout << fmt::format("{} on {}: {} configuration(s), wall {:.1f} s\n", o.scene, result.device.name,
                             result.configurations.size(),
                             (result.overhead.totalMs + result.overhead.reportMs) / 1000.0);
    std::cout << harness::sweepTable(result);
    std::cout << "  results in " << o.out << " (sweep.html, sweep.json, sweep.csv, sweep.md)\n";
  }
  return kExitOk;
}

static VerbRegistrar reg(30, [](CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* sub = app.add_subcommand(
      "sweep", "Run time against error over a grid of configurations; mark the Pareto front (sweep.html)");
  sub->add_option("scene", o->scene, "Scene file (scenes/*.json) or builtin:proof")->required();
  addCommonOptions(*sub, o->common);
  sub->add_option(
      "--vary", o->vary,
      "KEY=V1,V2,...: an axis of the grid (repeatable). KEY is msaa, width, height, size (WxH) or any --set knob");
  sub->add_option("--sweep", o->sweepFile, "A standard sweep (bench/sweeps/*.json); --vary adds or replaces axes");
  sub->add_option("--out", o->out, "Output directory (default: out/<scene>-sweep)");
  sub->add_flag("--until-stable", o->untilStable,
                "Sample each configuration until the 95% CI of its median frame time is within --stable-within "
                "(default on CPU devices unless --frames is given)");
  sub->add_option("--stable-within", o->stableWithin, "Stability target: CI half-width in percent of the median")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 50.0));
  sub->add_option("--max-frames", o->maxFrames, "Frame cap per configuration when sampling until stable")
      ->capture_default_str()
      ->check(CLI::Range(16u, 100000u));
  sub->add_option("--round-frames", o->roundFrames, "Frames per configuration per interleaved round")
      ->capture_default_str()
      ->check(CLI::Range(1u, 10000u));
  sub->add_option("--max-minutes", o->maxMinutes, "Start no new measuring round after this many minutes (0: no limit)")
      ->check(CLI::Range(0.0, 1e6));
  sub->add_option("--seed", o->seed, "Seed of the configurations' order in each round")->capture_default_str();
  sub->add_option("--reference-ssaa", o->referenceSsaa,
                  "SSAA of the reference (its convergence is checked one step down, and errors within 2x that gap are "
                  "marked unresolved): raise it when the gap is too large, up to what the device can hold")
      ->capture_default_str()
      ->check(CLI::Range(2u, 8u));
  sub->add_option("--shard", o->shard,
                  "K/N: measure only shard K of N of the grid, cut along reference groups (no reference is rendered "
                  "twice); run the N shards on N devices or machines, then `fgbench sweep-merge DIR...`");
  sub->add_option("--path-times", o->pathTimes,
                  "K: on a scene with a camera path, judge each configuration's error at K path times spread over "
                  "it (camera.time), each against its reference at that time; the front takes the mean (0: the "
                  "compared frame only)")
      ->capture_default_str()
      ->check(CLI::Range(0u, 64u));
  return Verb{sub, [sub, o] { return sweepVerb(*sub, *o); }};
});

}  // namespace
}  // namespace fgb::app
