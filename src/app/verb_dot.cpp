// fgbench dot SCENE [--detail brief|full] [-o FILE]: the compiled frame graph as Graphviz.
#include "verb.hpp"

#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/harness/run/run_loop.hpp>
#include <fgb/renderer/workload.hpp>

#include <filesystem>
#include <iostream>
#include <map>

namespace fgb::app {
namespace {

struct DotOptions {
  std::string scene;
  std::string detail = "brief";
  std::string output;  // empty: stdout
  CommonOptions common;
};

// -o names a file in a folder that must exist: a wrong path is bad input, found before rendering.
void checkOutputFolder(const std::string& output) {
  if (output.empty() || output == "-") return;
  const std::filesystem::path folder = std::filesystem::path(output).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder)) {
    throw InputError("-o " + output + ": folder " + folder.string() + " does not exist");
  }
}

int dotVerb(const DotOptions& o) {
  checkOutputFolder(o.output);
  const auto workload = render::openWorkload(workloadConfig(o.scene, o.common, harness::parseKnobs(o.common.sets)));
  const std::string dot =
      workload->graphviz(o.detail == "full" ? render::GraphDetail::Full : render::GraphDetail::Brief);
  if (o.output.empty() || o.output == "-") {
    std::cout << dot;
  } else {
    writeFileAtomic(o.output, dot);
    if (!o.common.quiet) std::cerr << "fgbench: wrote " << o.output << "\n";
  }
  return 0;
}

const VerbRegistrar reg(40, [](CLI::App& app) {
  auto options = std::make_shared<DotOptions>();
  CLI::App* sub = app.add_subcommand("dot", "Write the compiled frame graph of SCENE as Graphviz");
  sub->add_option("scene", options->scene, "Scene file (scenes/*.json) or builtin:proof")->required();
  sub->add_option("--detail", options->detail, "brief (nodes, resource flow) | full (+ barriers, queues, aliasing)")
      ->check(CLI::IsMember({"brief", "full"}))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output, "Output file (default: stdout)");
  addCommonOptions(*sub, options->common);
  return Verb{sub, [options] { return dotVerb(*options); }};
});

}  // namespace
}  // namespace fgb::app
