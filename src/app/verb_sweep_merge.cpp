// `fgbench sweep-merge DIR... [--out DIR]`: joins the outputs of `fgbench sweep --shard K/N` (one
// per device or machine) into one sweep.json/.csv/.md/.html, with the front computed over all
// configurations.
#include <fmt/format.h>

#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/results/golden.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/harness/sweep/sweep.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>
#include <iostream>

#include "verb.hpp"

namespace fgb::app {
namespace {

struct SweepMergeOptions {
  std::vector<std::string> shards;
  std::string out;
  bool json = false;
  bool quiet = false;
};

int sweepMergeVerb(const SweepMergeOptions& o) {
  std::vector<std::filesystem::path> dirs(o.shards.begin(), o.shards.end());
  harness::SweepResult result = harness::mergeSweepShards(dirs);
  const std::string out = o.out.empty() ? "out/" + harness::sceneName(result.scene) + "-sweep-merged" : o.out;
  harness::writeSweepOutputs(out, result);
  if (o.json) {
    std::cout << harness::dumpJson(harness::sweepJson(result));
  } else if (!o.quiet) {
    std::cout << fmt::format("{} on {}: {} configuration(s) from {} shard(s)\n", result.scene, result.device.name,
                             result.configurations.size(), result.mergedShards);
    std::cout << harness::sweepTable(result);
    std::cout << "  results in " << out << " (sweep.html, sweep.json, sweep.csv, sweep.md)\n";
  }
  return kExitOk;
}

static VerbRegistrar reg(31, [](CLI::App& app) {
  auto o = std::make_shared<SweepMergeOptions>();
  CLI::App* sub = app.add_subcommand(
      "sweep-merge",
      "Join the shards of a sweep (`fgbench sweep ... --shard K/N --out DIR_K`, one per device) into one sweep with "
      "one front; shards of different scenes, builds, device models or grids exit 2");
  sub->add_option("shards", o->shards, "Each shard's --out directory (or its sweep.json)")->required();
  sub->add_option("--out", o->out, "Output directory (default: out/<scene>-sweep-merged)");
  sub->add_flag("--json", o->json, "Machine-readable output on stdout");
  sub->add_flag("--quiet", o->quiet, "No table");
  return Verb{sub, [o] { return sweepMergeVerb(*o); }};
});

}  // namespace
}  // namespace fgb::app
