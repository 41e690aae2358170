// `fgbench compare-runs OLD NEW` (or --old ... --new ...): per-pass timing regression test between
// two sets of runs, on run-level statistics (harness/compare_runs.hpp); exit 1 on a significant
// slowdown beyond the thresholds, 0 otherwise (also for "unknown: add runs"), 2 for bad input.
#include "verb.hpp"

#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/results/compare_runs.hpp>

#include <fmt/format.h>

#include <iostream>

namespace fgb::app {
namespace {

struct CompareRunsVerbOptions {
  std::vector<std::string> positional;
  std::vector<std::string> before, after;
  harness::CompareRunsOptions test;
  bool json = false;
  bool quiet = false;
};

std::vector<harness::LoadedTimings> loadSide(const std::vector<std::string>& paths) {
  std::vector<harness::LoadedTimings> runs;
  for (const auto& path : paths) {
    for (const auto& file : harness::timingsFilesIn(path)) runs.push_back(harness::loadTimings(file));
  }
  return runs;
}

std::string sideName(const std::vector<std::string>& paths) {
  std::string name;
  for (const auto& p : paths) name += (name.empty() ? "" : " ") + p;
  return name;
}

int compareRunsVerb(CompareRunsVerbOptions o) {
  if (!o.positional.empty()) {
    if (o.positional.size() != 2 || !o.before.empty() || !o.after.empty()) {
      throw InputError("compare-runs: give OLD NEW, or --old PATH... --new PATH... (not both)");
    }
    o.before = {o.positional[0]};
    o.after = {o.positional[1]};
  }
  if (o.before.empty() || o.after.empty())
    throw InputError("compare-runs: give OLD NEW, or --old PATH... --new PATH...");
  const auto before = loadSide(o.before);
  const auto after = loadSide(o.after);
  for (const auto* side : {&before, &after}) {
    for (const auto& run : *side) {
      if (!run.scene.empty() && !before.front().scene.empty() && run.scene != before.front().scene) {
        std::cerr << fmt::format("fgbench: warning: comparing different scenes ({} in {} vs {})\n", run.scene, run.file,
                                 before.front().scene);
        break;
      }
    }
  }
  const harness::RunsComparison c = harness::compareRuns(before, after, o.test);
  if (o.json) {
    std::cout << harness::dumpJson(harness::toJson(c));
  } else if (!o.quiet) {
    std::cout << harness::formatTable(c);
  }
  if (c.anySlower()) {
    std::string slower;
    for (const auto& r : c.rows) {
      if (r.verdict == "slower")
        slower += fmt::format(" {} {:+.1f}% (p={:.2g});", r.pass, r.deltaRelative * 100.0, r.pSlower);
    }
    throw CheckFailed("significant slowdown in " + sideName(o.after) + " against " + sideName(o.before) + ":" + slower);
  }
  return kExitOk;
}

constexpr const char* kDescription =
    "Per-pass timing regression test between two sets of runs.\n"
    "Each side is one or more runs: a timings.json, a run's --out directory, or a directory of run\n"
    "directories (out/A/r1, out/A/r2, ...) or *.json files. Repetitions must be separate `fgbench run`\n"
    "processes, best interleaved A B A B ... (bench/ab-runs.sh does it):\n"
    "  fgbench compare-runs old/timings.json new/timings.json      one run a side\n"
    "  fgbench compare-runs out/A out/B                             every run under out/A vs out/B\n"
    "  fgbench compare-runs --old a1 --old a2 --new b1 --new b2     runs listed one by one\n"
    "Per pass, each run's median; a side is the geometric mean of its runs. A change is claimed when it is\n"
    "significant against the run-to-run noise (the runs' own spread, or the device class's measured model\n"
    "when that is larger) and at least --min-effect and --min-abs-ms. Verdicts: slower / faster / same /\n"
    "unknown (big enough to matter but inside the noise: add runs). 'detectable' is the smallest change\n"
    "these runs would find with probability --power. Exit 0: no slowdown (also unknown), 1: a pass is\n"
    "slower, 2: bad input.";

static VerbRegistrar reg(70, [](CLI::App& app) {
  auto o = std::make_shared<CompareRunsVerbOptions>();
  CLI::App* sub = app.add_subcommand("compare-runs", kDescription);
  sub->add_option("runs", o->positional, "OLD NEW: each a timings.json, a run directory or a directory of runs")
      ->expected(0, 2);
  sub->add_option("--old", o->before, "Baseline run(s): timings.json or directory (repeatable)");
  sub->add_option("--new", o->after, "New run(s): timings.json or directory (repeatable)");
  sub->add_option("--alpha", o->test.alpha, "One-sided significance level per pass")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 0.5));
  sub->add_option("--min-effect", o->test.minEffect, "Smallest relative change that counts (0.05 = 5%)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  sub->add_option("--min-abs-ms", o->test.minAbsMs, "Smallest absolute change that counts, ms")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  sub->add_option("--power", o->test.power, "Probability of finding the 'detectable' change")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 0.999));
  sub->add_option("--noise-class", o->test.deviceClass,
                  "Run-to-run noise model: cpu | discrete | integrated (default: the runs' device type)")
      ->check(CLI::IsMember({"cpu", "discrete", "integrated"}));
  sub->add_option("--run-noise", o->test.runNoise,
                  "Run-to-run relative noise of this machine (0.05 = 5%), measured e.g. with bench/ab-runs.sh, "
                  "instead of the device class's")
      ->check(CLI::Range(0.0, 10.0));
  sub->add_flag("--json", o->json, "Machine-readable output on stdout");
  sub->add_flag("--quiet", o->quiet, "No table");
  return Verb{sub, [o] { return compareRunsVerb(*o); }};
});

}  // namespace
}  // namespace fgb::app
