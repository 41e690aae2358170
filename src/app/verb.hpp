// Each CLI verb lives in its own verb_*.cpp and registers itself with a VerbRegistrar, so verbs can
// be added without touching main.cpp. A verb adds a CLI11 subcommand, binds its options, and returns
// the action to run once parsing succeeded. Actions return an exit code or throw fgb::InputError
// (exit 2), fgb::CheckFailed (exit 1) or fgb::DeviceError (exit 3); main maps them.
#pragma once

#include <CLI/CLI.hpp>
#include <fgb/core/knob_registry.hpp>
#include <fgb/renderer/workload.hpp>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fgb::app {

// Options shared by the rendering verbs (contract: "Common options").
struct CommonOptions {
  std::string device = "auto";
  uint32_t width = 0;   // 0: scene or verb default
  uint32_t height = 0;
  uint32_t msaa = 0;    // 0: scene default
  uint32_t frames = 64;
  uint32_t warmup = 8;
  std::vector<std::string> sets;  // key=value knobs
  bool json = false;
  bool verbose = false;
  bool quiet = false;
  bool validation = false;
  bool checkFinite = false;  // --check-finite
  double timeStep = 0.0;  // --time-step: seconds between frames (0: the scene's render.time_step, else 1/60)
};

// Adds the common rendering options to a subcommand, bound to `options`.
void addCommonOptions(CLI::App& command, CommonOptions& options);

// Every `--set` key the program knows: the scene layer's and the renderer's (fgb/core/knob_registry.hpp).
const KnobRegistry& knobRegistry();

// "key=value" assignments split and checked against knobRegistry(): InputError (exit 2) naming an
// unknown key (and the known ones) or a value of the wrong type or out of range.
std::map<std::string, std::string> checkedKnobs(const std::vector<std::string>& assignments);

// The workload a rendering verb opens: SCENE plus the common options and the given knobs (checked
// against knobRegistry() here, so knobs adopted from a golden's configuration are checked too).
render::WorkloadConfig workloadConfig(const std::string& scene, const CommonOptions& common,
                                      const std::map<std::string, std::string>& knobs);

using VerbAction = std::function<int()>;

// What a verb's registration returns: its subcommand and the action to run when it was chosen.
struct Verb {
  CLI::App* command = nullptr;
  VerbAction action;
};

struct VerbDefinition {
  int order;  // position in --help
  std::function<Verb(CLI::App& app)> add;
};

std::vector<VerbDefinition>& verbRegistry();

struct VerbRegistrar {
  VerbRegistrar(int order, std::function<Verb(CLI::App& app)> add) {
    verbRegistry().push_back({order, std::move(add)});
  }
};

}  // namespace fgb::app
