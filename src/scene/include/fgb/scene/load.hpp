// The one entry point for consumers: loadScene(scene.json, options) -> LoadedScene.
//
// A scene is assembled from parts -- the generator's output and each model file -- and every part
// goes through the cooked cache: a hit loads the cooked data (no importing, no cooking); a miss
// imports or generates, cooks, and stores. Then the scene file's lights, emitters, camera and post
// overrides and the --set knobs are applied (cheap, never cached).
//
// Model import (Assimp + OpenImageIO) lives in fgb_import, which registers itself with
// setModelImporter() (call fgb::import::enableModelImport(), or enableModelImportOnDemand(), which
// registers an importer that loads fgb_import as a module on its first call). Without it, fgb_scene
// still loads generators and cached models; a model cache miss is an InputError saying so.
#pragma once

#include <fgb/scene/scene.hpp>
#include <fgb/scene/scene_file.hpp>

#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fgb::scene {

// What an importer returns: an uncooked (but repaired) scene and the other files it read,
// relative to the model's directory, so the cache can notice when one of them changes.
struct ImportedModel {
  Scene scene;
  std::vector<std::string> dependencies;
};
using ModelImporter = std::function<ImportedModel(const std::filesystem::path& model)>;

// `signature` names the importer and its settings; it is part of model cache keys.
void setModelImporter(std::string signature, ModelImporter importer);
bool hasModelImporter();

struct LoadOptions {
  std::optional<std::filesystem::path> cacheDir;  // default: CookedCache::defaultDirectory()
  bool useCache = true;                           // false: never read or write cooked entries
  std::map<std::string, std::string> knobs;       // key -> value; only scene-owned keys are read
};

// How one part was obtained (for reports and for checking that a warm load skipped cooking).
struct PartLoad {
  std::string source;        // "generator:atrium" or the model path
  std::string cache;         // "hit", "miss", "rebuilt" (entry was corrupt/stale), "disabled"
  std::string key;           // cache key (32 hex digits)
  std::string entry;         // cache file path ("" when disabled)
  double produceMs = 0.0;    // import or generation (0 on a hit)
  double cookMs = 0.0;       // cooking (0 on a hit)
  double storeMs = 0.0;      // writing the entry (0 on a hit)
  double readMs = 0.0;       // reading + checksum + decoding the entry (0 on a miss)
};

struct LoadedScene {
  SceneDescription description;
  Scene scene;                        // cooked, GPU-ready
  std::vector<PartLoad> parts;
  std::vector<std::string> notices;   // loader events worth a line: corrupt entry rebuilt, ...
  std::string hash;                   // contentHash(scene): changes when anything rendered changes
  double totalMs = 0.0;
};

// Throws fgb::InputError (exit 2) naming the file and field for any bad input.
LoadedScene loadScene(const std::filesystem::path& sceneFile, const LoadOptions& options = {});

// The part list as JSON, for `fgbench scene` and run reports.
nlohmann::json toJson(const std::vector<PartLoad>& parts);

// A camera that frames `bounds` (used when neither the sources nor the file give one).
Camera fitCamera(const Aabb& bounds);

}  // namespace fgb::scene
