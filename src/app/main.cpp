// fgbench: headless benchmark and regression harness for a frame-graph Vulkan renderer.
// The verbs are in verb_*.cpp; this file parses the command line and maps errors to exit codes.
#include "verb.hpp"

#include <fgb/core/error.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/scene/knobs.hpp>
#ifdef FGBENCH_WITH_IMPORT
#include <fgb/import/module_loader.hpp>
#endif

#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>

namespace fgb::app {

std::vector<VerbDefinition>& verbRegistry() {
  static std::vector<VerbDefinition> registry;
  return registry;
}

void addCommonOptions(CLI::App& command, CommonOptions& options) {
  command.add_option("--device", options.device,
                     "auto (first discrete/integrated GPU, else lavapipe) | lavapipe | gpu | INDEX")
      ->capture_default_str();
  command.add_option("--width", options.width, "Render width in pixels (default: scene's)");
  command.add_option("--height", options.height, "Render height in pixels (default: scene's)");
  command.add_option("--msaa", options.msaa, "MSAA samples 1|2|4|8, clamped to the device's support")
      ->check(CLI::IsMember({1, 2, 4, 8}));
  command.add_option("--frames", options.frames, "Measured frames")->capture_default_str()
      ->check(CLI::Range(1u, 100000u));
  command.add_option("--warmup", options.warmup, "Warm-up frames before measuring")->capture_default_str();
  command.add_option("--set", options.sets, "Scene or renderer knob, key=value (repeatable)");
  command.add_flag("--json", options.json, "Machine-readable output on stdout");
  command.add_flag("-v,--verbose", options.verbose, "More output");
  command.add_flag("--quiet", options.quiet, "No progress output");
  command.add_flag("--check-finite", options.checkFinite,
                   "After every pass writing float colour data, count NaN, Inf and values above half of R16F's "
                   "maximum on the GPU (timings.json passes[i].non_finite; the report names the first bad pass)");
  command.add_flag("--validation", options.validation,
                   "Enable Vulkan validation (+ synchronization validation); any message fails with exit 3");
  command.add_option("--time-step", options.timeStep,
                     "Seconds between frames: the camera along its path (camera.path) and the particles' step "
                     "(default: the scene's render.time_step, else 1/60)")
      ->check(CLI::Range(1e-6, 60.0));
}

const KnobRegistry& knobRegistry() {
  static const KnobRegistry registry = [] {
    KnobRegistry r;
    r.add(scene::knobSpecs());
    r.add(render::rendererKnobSpecs());
    return r;
  }();
  return registry;
}

std::map<std::string, std::string> checkedKnobs(const std::vector<std::string>& assignments) {
  auto knobs = splitKnobAssignments(assignments);
  knobRegistry().checkAll(knobs);
  return knobs;
}

render::WorkloadConfig workloadConfig(const std::string& scene, const CommonOptions& common,
                                      const std::map<std::string, std::string>& knobs) {
  knobRegistry().checkAll(knobs);
  render::WorkloadConfig config;
  config.scenePath = scene;
  config.device = common.device;
  config.width = common.width;
  config.height = common.height;
  config.msaa = common.msaa;
  config.validation = common.validation;
  config.checkFinite = common.checkFinite;
  config.timeStep = common.timeStep;
  config.knobs = knobs;
  return config;
}

}  // namespace fgb::app

int main(int argc, char** argv) {
  using namespace fgb;
  CLI::App app{"fgbench — headless frame-graph renderer benchmark and regression harness.\n"
               "Renders scenes offscreen through a Vulkan frame graph, times every pass on the GPU,\n"
               "and compares frames and timings against goldens and budgets.\n"};
  app.require_subcommand(1);
#ifdef FGBENCH_WITH_IMPORT
  // Model files are imported (Assimp + OpenImageIO) on a cooked-cache miss, by libfgb_import.so,
  // loaded then and not before: most runs never import, and linking it would slow every start.
  // fgbench-gpu, the small binary carried to GPU machines, lacks this and loads only cooked scenes
  // and generators.
  import::enableModelImportOnDemand();
#endif
  app.set_version_flag("--version", std::string(FGBENCH_VERSION));

  auto& registry = app::verbRegistry();
  std::sort(registry.begin(), registry.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  std::vector<app::Verb> verbs;
  verbs.reserve(registry.size());
  for (auto& definition : registry) verbs.push_back(definition.add(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "fgbench: " << e.what() << " (see fgbench --help)\n";
    return kExitBadInput;
  }

  try {
    for (auto& verb : verbs) {
      if (verb.command->parsed()) return verb.action();
    }
    std::cerr << "fgbench: no verb given (see fgbench --help)\n";
    return kExitBadInput;
  } catch (const InputError& e) {
    std::cerr << "fgbench: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const CheckFailed& e) {
    std::cerr << "fgbench: check failed: " << e.what() << "\n";
    return kExitCheckFailed;
  } catch (const DeviceError& e) {
    std::cerr << "fgbench: device error: " << e.what() << "\n";
    return kExitDevice;
  } catch (const graph::GraphError& e) {
    std::cerr << "fgbench: frame graph: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "fgbench: runtime failure: " << e.what() << "\n";
    return kExitDevice;
  }
}
