// `fgbench run SCENE`: warm-up + measured frames, per-pass GPU timings, images, graph dumps and
// reports into --out DIR; optional budget and golden checks (exit 1 when either fails).
#include <fmt/format.h>

#include <cmath>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/base/progress.hpp>
#include <fgb/harness/passes/pass_capture.hpp>
#include <fgb/harness/passes/pass_golden.hpp>
#include <fgb/harness/report/dart.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/results/budget.hpp>
#include <fgb/harness/results/compare_runs.hpp>
#include <fgb/harness/results/golden.hpp>
#include <fgb/harness/run/render_path.hpp>
#include <fgb/harness/run/run_loop.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/renderer/workload.hpp>
#include <iostream>
#include <optional>

#include "verb.hpp"

namespace fgb::app {
namespace {

struct RunVerbOptions {
  CommonOptions common;
  std::string scene;
  std::string out;
  std::string budget;
  double tolerance = -1.0;
  std::string golden;
  bool dart = false;
  bool untilStable = false;
  std::string detect;  // --detect: the change to be able to detect, "2%" or "0.02"
  bool noIsolate = false;
  int isolateFrames = -1;  // -1: defaultIsolatedFrames(frames)
  std::string capture;     // --capture passes | NODE,NODE,...
  bool comparePasses = false;  // --compare-passes: judge the per-pass goldens even when the frame passes
  int asyncFrames = -1;    // -1: defaultAsyncFrames(frames)
  bool noDebugViews = false;
};

// --detect 2% | 0.02: a relative change in (0, 1).
double parseDetect(const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  double value = 0.0;
  std::size_t used = 0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size()) throw InputError("--detect " + text + ": not a number (e.g. 2% or 0.02)");
  if (percent) value /= 100.0;
  if (!(value > 0.0 && value < 1.0)) throw InputError("--detect " + text + ": must lie between 0 and 100%");
  return value;
}

// A golden fixes what it was rendered with; options the user did not give follow it, so that
// `run --golden` compares like with like.
void adoptGoldenConfig(const harness::Golden& golden, const CLI::App& command, CommonOptions& common,
                       std::map<std::string, std::string>& knobs) {
  if (!command.count("--width") && golden.config.width) common.width = golden.config.width;
  if (!command.count("--height") && golden.config.height) common.height = golden.config.height;
  if (!command.count("--msaa") && golden.config.msaa) common.msaa = golden.config.msaa;
  // Animated content (particles) depends on how many frames were rendered.
  if (!command.count("--frames") && golden.config.frames) common.frames = golden.config.frames;
  if (!command.count("--warmup") && golden.config.hasWarmup) common.warmup = golden.config.warmup;
  for (const auto& [key, value] : golden.config.knobs) knobs.try_emplace(key, value);  // --set wins
}

harness::RunArtifacts render(const RunVerbOptions& o, const std::map<std::string, std::string>& knobs) {
  harness::ProgressBar bar(std::cerr, "rendering", !o.common.quiet && harness::ProgressBar::stderrIsTerminal());
  harness::RenderRequest request;
  request.workload = workloadConfig(o.scene, o.common, knobs);
  if (!o.capture.empty()) {
    request.workload.capture = true;
    request.workload.captureNodes = harness::parseCaptureList(o.capture);
  }
  request.warmup = o.common.warmup;
  request.frames = o.common.frames;
  if (o.untilStable) request.untilStable = harness::StabilityRule{};
  if (!o.detect.empty()) {
    request.untilStable = harness::StabilityRule{};
    request.untilStable->relativeHalfWidth = harness::halfWidthForDetectable(parseDetect(o.detect));
  }
  request.graphDumps = true;
  if (!o.noIsolate) {
    request.isolateFrames =
        o.isolateFrames >= 0 ? static_cast<uint32_t>(o.isolateFrames) : harness::defaultIsolatedFrames(request.frames);
  }
  request.asyncFrames =
      o.asyncFrames >= 0 ? static_cast<uint32_t>(o.asyncFrames) : harness::defaultAsyncFrames(request.frames);
  request.slowestFrames = 3;  // along a camera path: the report's thumbnails
  request.debugViews = !o.noDebugViews;
  request.progress = [&](uint32_t done, uint32_t total) { bar.update(done, total); };
  harness::RunArtifacts a = harness::renderConfiguration(render::openWorkload, request);
  bar.finish();
  a.run.toolVersion = FGBENCH_VERSION;
  return a;
}

void printSummary(const harness::RunResult& run, const std::string& out) {
  std::cout << fmt::format("{} on {}: {}x{}, {} frames\n", run.scene, run.device.name, run.config.width, run.config.height,
                           run.config.frames);
  for (const auto& p : run.passes) {
    if (p.culled) {
      std::cout << fmt::format("  {:<28} culled\n", p.name);
    } else {
      const double detectable = harness::detectableFromFrames(p.judgedSamples());
      std::cout << fmt::format("  {:<28} {:>9.4f} ms (p5 {:.4f}, p95 {:.4f}){}{}{}{}\n", p.name, p.gpu.median, p.gpu.p5,
                               p.gpu.p95, p.hasIsolated() ? fmt::format("  isolated {:.4f}", p.isolated.median) : "",
                               p.criticalShare >= 0.0 ? fmt::format("  critical {:.0f}%", 100.0 * p.criticalShare) : "",
                               std::isfinite(detectable) ? fmt::format("  detects {:.1f}%", 100.0 * detectable) : "",
                               p.unstable ? "  unstable" : "");
    }
  }
  std::cout << fmt::format("  {:<28} {:>9.4f} ms GPU, {:.4f} ms CPU", "frame", run.frameGpu.median,
                           run.frameCpu.median);
  if (const auto recorded = run.stats.find("nodes_recorded"); recorded != run.stats.end()) {
    std::cout << fmt::format(" (recorded {:g} / reused {:g} nodes, submit {:.4f} ms)", recorded->second,
                             run.stats.at("nodes_reused"), run.frameSubmit.median);
  }
  std::cout << "\n";
  if (run.device.hostTimestamps) std::cout << "  note: " << harness::timestampSourceNote(run.device) << "\n";
  std::cout << "  clock: " << harness::describeWallClock(run.wallClock) << "\n";
  if (run.asyncCompute.compared()) std::cout << "  " << harness::describeAsync(run.asyncCompute) << "\n";
  if (!run.deviceState.source.empty()) std::cout << "  " << harness::describeDeviceState(run.deviceState) << "\n";
  if (run.deviceState.clocksChanged()) std::cerr << "warning: the GPU's clocks changed during measurement\n";
  if (run.checkedFinite) {
    const auto* bad = run.firstNonFinite();
    std::cout << "  non-finite: " << (bad ? "first produced by " + bad->pass : std::string("none")) << "\n";
  }
  if (run.budget) std::cout << "  budget: " << run.budget->verdict << " (" << run.budget->judgedOn() << ")\n";
  if (run.golden) std::cout << "  golden: " << run.golden->verdict << "\n";
  if (!run.firstDifference.empty()) std::cout << "  passes: " << run.firstDifference << "\n";
  std::cout << "  results in " << out << "\n";
}

// One line naming what failed, for stderr and the CheckFailed exception.
std::string failureLine(const harness::RunResult& run) {
  std::string line;
  if (run.budget && run.budget->verdict == "fail") {
    line += "budget " + run.budget->file + ":";
    for (const auto* l : run.budget->failing()) {
      line += l->status == "missing" ? fmt::format(" {} not measured;", l->pass)
                                     : fmt::format(" {} {:.4f} ms > {:.3f} ms (+{:.1f}%);", l->pass, *l->measuredMs, l->budgetMs,
                                                   l->overPercent());
    }
  }
  if (run.golden && run.golden->verdict == "fail") {
    line += (line.empty() ? "" : " ") + std::string("golden ") + run.golden->file + ":";
    for (const auto& image : run.golden->images) {
      for (const auto& f : image.failures) line += " " + image.kind + " " + f + ";";
    }
    if (!run.golden->diffImage.empty()) line += " heat map " + run.golden->diffImage;
    if (!run.firstDifference.empty()) line += "; " + run.firstDifference;
  } else if (run.passesGolden.is_object() && !run.passesGolden["differing"].empty()) {
    // --compare-passes: the frame passed, but a pass moved beyond its noise.
    line += (line.empty() ? "" : " ") + std::string("per-pass goldens: ") + run.firstDifference;
  }
  return line;
}

int runVerb(const CLI::App& command, RunVerbOptions o) {
  auto knobs = harness::parseKnobs(o.common.sets);
  // Inputs are checked before rendering: a bad budget or a missing golden fails fast (exit 2).
  std::optional<harness::Budget> budget;
  if (!o.budget.empty()) budget = harness::loadBudget(o.budget);
  std::optional<harness::Golden> golden;
  if (!o.golden.empty()) {
    golden = harness::loadGolden(o.golden);
    adoptGoldenConfig(*golden, command, o.common, knobs);
    // Per-pass goldens beside it: capture every pass, to say where a failing frame went wrong.
    std::error_code ec;
    if (o.capture.empty() &&
        std::filesystem::is_regular_file(harness::passGoldenDir(golden->jsonPath) / "passes.json", ec))
      o.capture = "passes";
  }
  if (o.out.empty()) o.out = "out/" + harness::sceneName(o.scene);

  harness::RunArtifacts artifacts = render(o, knobs);
  harness::RunResult& run = artifacts.run;
  if (budget) run.budget = harness::checkBudget(*budget, run.medians(), o.tolerance);
  if (golden) run.golden = harness::checkGolden(*golden, artifacts.images, o.out, &artifacts.golden);
  if (golden && (run.golden->verdict == "fail" || o.comparePasses))
    harness::localiseAgainstPassGoldens(*golden, artifacts);
  harness::writeRunOutputs(o.out, artifacts);

  if (o.common.json) {
    std::cout << harness::dumpJson(harness::toJson(run));
  } else if (!o.common.quiet) {
    printSummary(run, o.out);
  }
  if (o.dart) std::cout << harness::dartMeasurements(run);
  const std::string failure = failureLine(run);
  if (!failure.empty()) throw CheckFailed(failure);
  return kExitOk;
}

static VerbRegistrar reg(20, [](CLI::App& app) {
  auto options = std::make_shared<RunVerbOptions>();
  CLI::App* sub = app.add_subcommand("run", "Render SCENE headless; write frames, timings, graph dumps and reports");
  sub->add_option("scene", options->scene, "Scene file (scenes/*.json) or builtin:proof")->required();
  addCommonOptions(*sub, options->common);
  sub->add_option("--out", options->out, "Output directory (default: out/<scene>)");
  sub->add_option("--budget", options->budget, "Per-pass budget JSON (bench/budgets/*.json); exit 1 when over");
  sub->add_option("--tolerance", options->tolerance, "Budget tolerance as a fraction (default: the budget file's)")
      ->check(CLI::Range(0.0, 10.0));
  sub->add_option("--golden", options->golden,
                  "Golden JSON (golden/<scene>/<device-class>/<config>.json) or its directory; exit 1 over threshold");
  sub->add_option("--capture", options->capture,
                  "Write the last frame's output images of each node to OUT/passes/ (with passes.json and the "
                  "culling counts in stats.json): 'passes' for every node, or NODE,NODE,...");
  sub->add_flag("--compare-passes", options->comparePasses,
                "With --golden: compare every pass with its per-pass golden even when the frame passes, and fail "
                "(exit 1) when one differs beyond its noise (checks that unchanged runs show no difference)");
  sub->add_flag("--dart", options->dart, "Print <DartMeasurement> tags for CTest/CDash");
  sub->add_flag("--until-stable", options->untilStable,
                "Measure until the 95% CI of the median frame time is within +-2% (--frames is the cap)");
  sub->add_flag(
      "--no-isolate", options->noIsolate,
      "Skip the calibration that times each pass alone on an idle device (isolated cost, critical-path share)");
  sub->add_option("--isolate-frames", options->isolateFrames,
                  "Calibration frames for the isolated costs (default: a quarter of --frames, 3 to 16; 0 skips)")
      ->check(CLI::Range(0, 1024));
  sub->add_option("--async-frames", options->asyncFrames,
                  "Frames rendered again with every pass on the graphics queue (render.async=0), to state what "
                  "async compute saved; only where the frame ran on two or more queues (default: a quarter of "
                  "--frames, 8 to 32; 0 skips)")
      ->check(CLI::Range(0, 1024));
  sub->add_flag("--no-debug-views", options->noDebugViews,
                "Skip the pictures of the clusters (debug-lod.png, debug-clusters.png: the frame again with "
                "debug.view=lod and =clusters) that paths drawing clusters (visbuffer, meshlet) add to the report");
  sub->add_option("--detect", options->detect,
                  "Measure until a change this small in the frame time is detectable (e.g. 2% or 0.02; alpha 0.05, "
                  "power 0.8, against the frames' own noise: compare-runs adds the run-to-run noise); --frames is "
                  "the cap");
  return Verb{sub, [sub, options] { return runVerb(*sub, *options); }};
});

}  // namespace
}  // namespace fgb::app
