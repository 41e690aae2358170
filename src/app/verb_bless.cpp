// `fgbench bless SCENE`: renders the scene several times, measures the run-to-run noise, and
// replaces golden/<scene>/<device-class>/<config>.{png,exr,json} — each file atomically, images
// before the JSON that refers to them. Never blesses a render with NaN/Inf.
#include <fmt/chrono.h>
#include <fmt/format.h>

#include <chrono>
#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/base/progress.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/passes/pass_golden.hpp>
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

// Goldens are small and quick to render in CTest on lavapipe.
constexpr uint32_t kBlessWidth = 640, kBlessHeight = 360, kBlessFrames = 16, kBlessWarmup = 4;

struct BlessOptions {
  CommonOptions common;
  std::string scene;
  std::string goldenRoot;
  std::string config = harness::kDefaultGoldenConfig;
  uint32_t renders = 3;
  bool resetThresholds = false;
  bool passes = false;  // --passes: per-pass goldens beside the frame's
};

struct Render {
  harness::Image display, hdr;  // quantised exactly as the golden files store them
  render::DeviceDescription device;
  std::map<std::string, double> stats;
  std::optional<harness::PassCaptureSet> passes;
};

// Next to the scenes: <dir>/scenes/x.json -> <dir>/golden; otherwise ./golden.
std::filesystem::path defaultGoldenRoot(const std::string& scene) {
  const std::filesystem::path dir = std::filesystem::path(scene).parent_path();
  if (!dir.empty() && dir.filename() == "scenes") return dir.parent_path() / "golden";
  return "golden";
}

Render renderOnce(const render::WorkloadConfig& config, const BlessOptions& o, uint32_t index) {
  harness::ProgressBar bar(std::cerr, fmt::format("bless render {}/{}", index + 1, o.renders),
                           !o.common.quiet && harness::ProgressBar::stderrIsTerminal());
  harness::RenderRequest request;
  request.workload = config;
  request.warmup = o.common.warmup;
  request.frames = o.common.frames;
  request.progress = [&](uint32_t done, uint32_t total) { bar.update(done, total); };
  const harness::RunArtifacts a = harness::renderConfiguration(render::openWorkload, request);
  bar.finish();
  return {harness::quantizeToSrgb8(a.images.display), harness::quantizeToHalf(a.images.hdr), a.run.device, a.run.stats,
          a.passes};
}

// The largest difference between the first render and any other: what "the same" looks like.
std::optional<harness::ImageMetrics> worstNoise(const std::vector<Render>& renders, bool hdr) {
  std::optional<harness::ImageMetrics> worst;
  for (std::size_t k = 1; k < renders.size(); ++k) {
    const auto& a = hdr ? renders[0].hdr : renders[0].display;
    const auto& b = hdr ? renders[k].hdr : renders[k].display;
    if (a.width != b.width || a.height != b.height) throw DeviceError("repeated renders differ in size");
    const harness::ImageMetrics m = harness::compareImages(a, b).metrics;
    if (!worst || (m.flip && worst->flip && m.flip->mean > worst->flip->mean) || m.rmse > worst->rmse) worst = m;
  }
  return worst;
}

nlohmann::json existingThresholds(const std::filesystem::path& jsonPath) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(jsonPath, ec)) return nullptr;
  const nlohmann::json doc = harness::readJsonFile(jsonPath);
  return doc.contains("thresholds") ? doc["thresholds"] : nlohmann::json(nullptr);
}

nlohmann::json goldenDocument(const BlessOptions& o, const render::WorkloadConfig& config, const std::vector<Render>& renders,
                              const nlohmann::json& keptThresholds) {
  const auto displayNoise = worstNoise(renders, false);
  const auto hdrNoise = worstNoise(renders, true);
  const Render& first = renders.front();
  nlohmann::json knobs = nlohmann::json::object();
  for (const auto& [k, v] : config.knobs) knobs[k] = v;
  nlohmann::json thresholds = keptThresholds.is_object()
                                  ? keptThresholds
                                  : nlohmann::json{{"display", harness::toJson(harness::thresholdsFromNoise(displayNoise, false))},
                                                   {"hdr", harness::toJson(harness::thresholdsFromNoise(hdrNoise, true))}};
  const auto msaa = first.stats.find("msaa");
  return {
      {"schema", 1},
      {"scene", o.scene},
      {"images", {{"display", o.config + ".png"}, {"hdr", o.config + ".exr"}}},
      {"config", {{"width", first.display.width}, {"height", first.display.height}, {"msaa", config.msaa},
                  {"frames", o.common.frames}, {"warmup", o.common.warmup}, {"knobs", knobs}}},
      {"thresholds", thresholds},
      {"made", {{"tool_version", FGBENCH_VERSION},
                {"date", fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())))},
                {"device", first.device.name}, {"driver", first.device.driver}, {"device_type", first.device.type},
                {"api_version", first.device.apiVersion}, {"device_class", harness::deviceClass(first.device)},
                {"msaa_used", msaa != first.stats.end() ? nlohmann::json(msaa->second) : nlohmann::json(nullptr)},
                {"scene_hash", harness::sceneHash(o.scene)}, {"renders", renders.size()},
                {"noise", {{"display", displayNoise ? harness::toJson(*displayNoise) : nlohmann::json(nullptr)},
                           {"hdr", hdrNoise ? harness::toJson(*hdrNoise) : nlohmann::json(nullptr)}}}}},
  };
}

// <config>/passes/: the first render's captures with thresholds from the noise between all renders.
void writePassGoldens(const std::filesystem::path& dir, const std::vector<Render>& renders,
                      const nlohmann::json& made) {
  std::vector<harness::PassCaptureSet> sets;
  for (const Render& render : renders) sets.push_back(*render.passes);
  harness::CaptureExtras extras = harness::passGoldenExtras(sets);
  extras.made = made;
  harness::writeCaptureSet(dir, sets.front(), extras);
}

int blessVerb(const CLI::App& command, BlessOptions o) {
  if (!command.count("--width")) o.common.width = kBlessWidth;
  if (!command.count("--height")) o.common.height = kBlessHeight;
  if (!command.count("--frames")) o.common.frames = kBlessFrames;
  if (!command.count("--warmup")) o.common.warmup = kBlessWarmup;
  render::WorkloadConfig config = workloadConfig(o.scene, o.common, harness::parseKnobs(o.common.sets));
  config.capture = o.passes;

  std::vector<Render> renders;
  for (uint32_t i = 0; i < o.renders; ++i) renders.push_back(renderOnce(config, o, i));
  const Render& first = renders.front();
  const std::size_t broken = harness::countNonFinite(first.hdr) + harness::countNonFinite(first.display);
  if (broken > 0) throw CheckFailed(fmt::format("{}: render has {} NaN/Inf pixels; golden not replaced", o.scene, broken));

  const std::filesystem::path root = o.goldenRoot.empty() ? defaultGoldenRoot(o.scene) : std::filesystem::path(o.goldenRoot);
  const std::filesystem::path dir = root / harness::sceneName(o.scene) / harness::deviceClass(first.device);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the golden directory (" + ec.message() + ")");
  const std::filesystem::path jsonPath = dir / (o.config + ".json");
  const nlohmann::json kept = o.resetThresholds ? nlohmann::json(nullptr) : existingThresholds(jsonPath);
  const nlohmann::json document = goldenDocument(o, config, renders, kept);

  harness::writePng(dir / (o.config + ".png"), first.display);
  harness::writeExr(dir / (o.config + ".exr"), first.hdr);
  if (o.passes) writePassGoldens(harness::passGoldenDir(jsonPath), renders, document["made"]);
  writeFileAtomic(jsonPath, harness::dumpJson(document));
  if (!o.common.quiet) {
    std::cout << fmt::format("blessed {} ({}x{}, {} renders) -> {}\n", o.scene, first.display.width, first.display.height,
                             renders.size(), jsonPath.string());
  }
  return kExitOk;
}

static VerbRegistrar reg(60, [](CLI::App& app) {
  auto o = std::make_shared<BlessOptions>();
  CLI::App* sub = app.add_subcommand("bless", "Render SCENE and atomically replace its golden images and metadata");
  sub->add_option("scene", o->scene, "Scene file (scenes/*.json) or builtin:proof")->required();
  addCommonOptions(*sub, o->common);
  sub->add_option("--golden-root", o->goldenRoot, "Golden tree root (default: golden/ next to scenes/)");
  sub->add_option("--config", o->config, "Golden configuration name (file stem)")->capture_default_str();
  sub->add_option("--renders", o->renders, "Repeated renders to measure noise")->capture_default_str()->check(CLI::Range(1u, 100u));
  sub->add_flag("--passes", o->passes,
                "Also store per-pass goldens (every node's output images and culling counts, with their noise) in "
                "<config>/passes/, which localise a failing frame to the pass where it first differs");
  sub->add_flag("--reset-thresholds", o->resetThresholds, "Derive thresholds from the measured noise, replacing edited ones");
  return Verb{sub, [sub, o] { return blessVerb(*sub, *o); }};
});

}  // namespace
}  // namespace fgb::app
