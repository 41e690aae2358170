// `fgbench compare-runs OLD NEW`: per-pass Mann–Whitney U test plus a minimum effect size between
// two timings.json files; exit 1 on a significant slowdown beyond the threshold.
#include "verb.hpp"

#include <fgb/core/error.hpp>
#include <fgb/harness/compare_runs.hpp>
#include <fgb/harness/json_io.hpp>

#include <fmt/format.h>

#include <iostream>

namespace fgb::app {
namespace {

struct CompareRunsVerbOptions {
  std::string before, after;
  harness::CompareRunsOptions test;
  bool json = false;
  bool quiet = false;
};

int compareRunsVerb(const CompareRunsVerbOptions& o) {
  const harness::LoadedTimings before = harness::loadTimings(o.before);
  const harness::LoadedTimings after = harness::loadTimings(o.after);
  if (!before.scene.empty() && !after.scene.empty() && before.scene != after.scene) {
    std::cerr << fmt::format("fgbench: warning: comparing different scenes ({} vs {})\n", before.scene, after.scene);
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
      if (r.verdict == "slower") slower += fmt::format(" {} {:+.1f}% (p={:.2g});", r.pass, r.deltaRelative * 100.0, r.test.pAGreater);
    }
    throw CheckFailed("significant slowdown in " + o.after + " against " + o.before + ":" + slower);
  }
  return kExitOk;
}

static VerbRegistrar reg(70, [](CLI::App& app) {
  auto o = std::make_shared<CompareRunsVerbOptions>();
  CLI::App* sub = app.add_subcommand("compare-runs", "Per-pass timing regression test between two timings.json files");
  sub->add_option("old", o->before, "Baseline timings.json")->required();
  sub->add_option("new", o->after, "New timings.json")->required();
  sub->add_option("--alpha", o->test.alpha, "One-sided significance level")->capture_default_str()->check(CLI::Range(1e-9, 0.5));
  sub->add_option("--min-effect", o->test.minEffect, "Smallest relative median change that counts (0.05 = 5%)")
      ->capture_default_str()->check(CLI::Range(0.0, 10.0));
  sub->add_option("--min-abs-ms", o->test.minAbsMs, "Smallest absolute median change that counts, ms")
      ->capture_default_str()->check(CLI::Range(0.0, 1e6));
  sub->add_flag("--json", o->json, "Machine-readable output on stdout");
  sub->add_flag("--quiet", o->quiet, "No table");
  return Verb{sub, [o] { return compareRunsVerb(*o); }};
});

}  // namespace
}  // namespace fgb::app
