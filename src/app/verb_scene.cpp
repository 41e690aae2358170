// `fgbench scene SCENE`: loads a scene through the cooked cache and prints its statistics as JSON
// (instances, meshes, triangles, lights, emitters, materials, textures, bounds, repairs), plus how
// each part was obtained (cache hit or miss, with timings). Warnings go to stderr, one line each.
#include "verb.hpp"

#include <fgb/core/error.hpp>
#include <fgb/scene/load.hpp>
#include <fgb/scene/stats.hpp>

#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace fgb::app {
namespace {

struct SceneVerbOptions {
  std::string scene;
  std::string cache;
  bool noCache = false;
  std::vector<std::string> sets;
  uint32_t width = 1920;
  uint32_t height = 1080;
  bool json = true;
  bool quiet = false;
};

nlohmann::json describe(const scene::LoadedScene& loaded, float aspect) {
  nlohmann::json out = scene::toJson(scene::stats(loaded.scene, aspect));
  out["scene"] = loaded.description.path.string();
  out["name"] = loaded.description.name;
  out["scene_hash"] = loaded.hash;
  out["camera"] = scene::toJson(loaded.scene.camera);
  out["post"] = {{"exposure", loaded.scene.post.exposure},
                 {"bloom",
                  {{"enabled", loaded.scene.post.bloom.enabled},
                   {"threshold", loaded.scene.post.bloom.threshold},
                   {"knee", loaded.scene.post.bloom.knee},
                   {"intensity", loaded.scene.post.bloom.intensity},
                   {"radius", loaded.scene.post.bloom.radius}}}};
  out["warnings"] = loaded.scene.warnings;
  out["load"] = {{"parts", scene::toJson(loaded.parts)}, {"total_ms", loaded.totalMs}, {"notices", loaded.notices}};
  return out;
}

int runScene(const SceneVerbOptions& options) {
  scene::LoadOptions load;
  if (!options.cache.empty()) load.cacheDir = options.cache;
  load.useCache = !options.noCache;
  load.knobs = checkedKnobs(options.sets);  // every key known to some layer, every value in range
  const scene::LoadedScene loaded = scene::loadScene(options.scene, load);
  if (!options.quiet) {
    for (const std::string& warning : loaded.scene.warnings) std::cerr << "fgbench: warning: " << warning << "\n";
    for (const std::string& notice : loaded.notices) std::cerr << "fgbench: " << notice << "\n";
  }
  const float aspect = float(options.width) / float(options.height);
  std::cout << describe(loaded, aspect).dump(2) << "\n";
  return kExitOk;
}

VerbRegistrar registrar(40, [](CLI::App& app) {
  auto options = std::make_shared<SceneVerbOptions>();
  CLI::App* command = app.add_subcommand("scene", "Scene statistics as JSON (instances, meshes, triangles, lights, "
                                                  "emitters, materials, textures, bounds, repairs)");
  command->add_option("SCENE", options->scene, "Scene file (scenes/*.json)")->required();
  command->add_option("--cache", options->cache, "Cooked-asset cache directory (default: $XDG_CACHE_HOME/fgbench)");
  command->add_flag("--no-cache", options->noCache, "Import/generate and cook without reading or writing the cache");
  command->add_option("--set", options->sets, "Scene knob key=value (repeatable), e.g. atrium.scale=8");
  command->add_option("--width", options->width, "Width for the visibility count's aspect ratio")->capture_default_str();
  command->add_option("--height", options->height, "Height for the visibility count's aspect ratio")->capture_default_str();
  command->add_flag("--json", options->json, "JSON on stdout (always on for this verb)");
  command->add_flag("--quiet", options->quiet, "Do not print warnings on stderr");
  return Verb{command, [options] { return runScene(*options); }};
});

}  // namespace
}  // namespace fgb::app
