// loadScene: parts through the cooked cache, then scene-file and knob overrides.
#include <fgb/scene/load.hpp>
#include <fgb/scene/camera_path.hpp>

#include <fgb/core/error.hpp>
#include <fgb/scene/cache.hpp>
#include <fgb/scene/code_hash.hpp>
#include <fgb/scene/cook.hpp>
#include <fgb/scene/generators.hpp>
#include <fgb/scene/geometry.hpp>
#include <fgb/scene/knobs.hpp>
#include <fgb/scene/stats.hpp>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <mutex>

namespace fgb::scene {
namespace {

struct ImporterSlot {
  std::mutex mutex;
  std::string signature;
  ModelImporter importer;
};

ImporterSlot& importerSlot() {
  static ImporterSlot slot;
  return slot;
}

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Produced {
  Scene scene;
  std::vector<CacheDependency> dependencies;
};

class PartLoader {
 public:
  PartLoader(const LoadOptions& options, LoadedScene& result)
      : cache_(options.cacheDir ? *options.cacheDir : CookedCache::defaultDirectory()),
        useCache_(options.useCache),
        result_(result) {}

  // Returns the cooked part: from the cache when possible, else produced, cooked and stored.
  Scene load(const std::string& source, const std::string& key, const std::filesystem::path& baseDir,
             const std::function<Produced()>& produce) {
    PartLoad info;
    info.source = source;
    info.key = key;
    info.cache = useCache_ ? "miss" : "disabled";
    if (useCache_) {
      info.entry = cache_.entryPath(key).string();
      CacheLookup lookup = cache_.load(key, baseDir);
      if (lookup.status == CacheStatus::Hit) {
        info.cache = "hit";
        info.readMs = lookup.readMs;
        result_.parts.push_back(info);
        return std::move(*lookup.scene);
      }
      if (lookup.status == CacheStatus::Corrupt || lookup.status == CacheStatus::Stale) {
        info.cache = "rebuilt";
        result_.notices.push_back("cooked cache entry for " + source + " was " + toString(lookup.status) + " (" +
                                  lookup.reason + "); rebuilt");
      }
    }
    auto start = Clock::now();
    Produced produced = produce();
    info.produceMs = msSince(start);
    start = Clock::now();
    cookScene(produced.scene);
    info.cookMs = msSince(start);
    if (useCache_) {
      start = Clock::now();
      try {
        cache_.store(key, produced.scene, produced.dependencies);
      } catch (const std::exception& e) {
        // A read-only or full cache must not stop a run; the next run simply cooks again.
        result_.notices.push_back(std::string("could not store cooked cache entry: ") + e.what());
      }
      info.storeMs = msSince(start);
    }
    result_.parts.push_back(info);
    return std::move(produced.scene);
  }

 private:
  CookedCache cache_;
  bool useCache_;
  LoadedScene& result_;
};

// What cooked output depends on besides its input: the cooker's format version and the scene code
// that produced it (a change to either cooks again). Every part's key ends with it.
CacheKey& addCookingCode(CacheKey& key) {
  return key.add(std::to_string(kCookerVersion)).add(kSceneCodeHash);
}

Scene loadGenerator(PartLoader& loader, const SceneDescription& d, const Knobs& knobs) {
  const GeneratorRef& generator = *d.generator;
  const nlohmann::json params = resolveGeneratorParams(generator, knobs, d.path.string());
  CacheKey key;
  addCookingCode(key.add("generator").add(generator.type).add(params.dump()));
  return loader.load("generator:" + generator.type, key.finish(), {}, [&] {
    return Produced{generate(generator.type, params), {}};
  });
}

Scene loadModel(PartLoader& loader, const SceneDescription& d, const ModelRef& model) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(model.file, error)) {
    throw InputError(d.path.string() + ": field '" + model.field + "': model file " + model.file.string() +
                     " not found");
  }
  std::string signature;
  ModelImporter importer;
  {
    ImporterSlot& slot = importerSlot();
    std::lock_guard lock(slot.mutex);
    signature = slot.signature;
    importer = slot.importer;
  }
  CacheKey key;
  addCookingCode(key.add("model").addFile(model.file).add(signature));
  const std::filesystem::path baseDir = model.file.parent_path();
  return loader.load(model.file.string(), key.finish(), baseDir, [&] {
    if (!importer) {
      throw InputError(model.file.string() + ": no cooked cache entry, and this build has no model import support; "
                       "cook it once with a full build (fgbench scene) using the same --cache");
    }
    ImportedModel imported = importer(model.file);
    Produced produced{std::move(imported.scene), {}};
    for (const std::string& dependency : imported.dependencies) {
      if (auto described = describeDependency(baseDir, dependency)) produced.dependencies.push_back(*described);
    }
    return produced;
  });
}

void applyDescription(Scene& scene, const SceneDescription& d) {
  scene.lights.insert(scene.lights.end(), d.lights.begin(), d.lights.end());
  scene.emitters.insert(scene.emitters.end(), d.emitters.begin(), d.emitters.end());
  if (d.sun) scene.sun = *d.sun;
  if (!scene.hasCamera) {
    scene.camera = fitCamera(scene.bounds());
    scene.hasCamera = true;
  }
  applyCameraOverrides(scene.camera, d.camera, d.path.string());
  if (d.camera.is_object() && d.camera.contains("path")) scene.cameraPath = parseCameraPath(d.camera["path"], d.path.string());
  applyPostOverrides(scene.post, d.post, d.path.string());
}

}  // namespace

void setModelImporter(std::string signature, ModelImporter importer) {
  ImporterSlot& slot = importerSlot();
  std::lock_guard lock(slot.mutex);
  slot.signature = std::move(signature);
  slot.importer = std::move(importer);
}

bool hasModelImporter() {
  ImporterSlot& slot = importerSlot();
  std::lock_guard lock(slot.mutex);
  return static_cast<bool>(slot.importer);
}

Camera fitCamera(const Aabb& bounds) {
  Camera camera;
  if (bounds.isEmpty()) return camera;
  const glm::dvec3 centre = (bounds.min + bounds.max) * 0.5;
  const double radius = std::max(0.5 * glm::length(bounds.max - bounds.min), 1e-3);
  camera.target = centre;
  camera.position = centre + glm::dvec3(0.0, 0.35, 1.0) * (radius * 2.0);
  camera.nearPlane = static_cast<float>(radius * 0.01);
  camera.farPlane = static_cast<float>(radius * 20.0);
  return camera;
}

LoadedScene loadScene(const std::filesystem::path& sceneFile, const LoadOptions& options) {
  const auto start = Clock::now();
  LoadedScene result;
  result.description = parseSceneFile(sceneFile);
  const Knobs knobs = Knobs::from(options.knobs);
  const SceneDescription& d = result.description;
  PartLoader loader(options, result);

  Scene scene;
  if (d.generator) scene = loadGenerator(loader, d, knobs);
  for (const ModelRef& model : d.models) mergeScene(scene, loadModel(loader, d, model), model.placement);
  applyDescription(scene, d);
  applyKnobs(scene, knobs);
  result.scene = std::move(scene);
  result.hash = contentHash(result.scene);
  result.totalMs = msSince(start);
  return result;
}

nlohmann::json toJson(const std::vector<PartLoad>& parts) {
  nlohmann::json list = nlohmann::json::array();
  for (const PartLoad& p : parts) {
    list.push_back({{"source", p.source},     {"cache", p.cache},    {"key", p.key},        {"entry", p.entry},
                    {"produce_ms", p.produceMs}, {"cook_ms", p.cookMs}, {"store_ms", p.storeMs}, {"read_ms", p.readMs}});
  }
  return list;
}

}  // namespace fgb::scene
