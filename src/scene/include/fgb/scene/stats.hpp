// Scene statistics (what `fgbench scene` prints and the run report quotes) and their JSON form.
#pragma once

#include <fgb/scene/scene.hpp>

#include <nlohmann/json_fwd.hpp>

#include <cstdint>

namespace fgb::scene {

struct SceneStats {
  uint32_t instances = 0;
  uint32_t instancesVisible = 0;   // against scene.camera at `aspect`
  uint32_t meshes = 0;
  uint64_t triangles = 0;          // summed over instances: what a frame draws before culling
  uint64_t trianglesVisible = 0;
  uint64_t uniqueTriangles = 0;    // summed over meshes: what the GPU stores
  uint64_t vertices = 0;
  uint32_t lights = 0;
  bool directionalLight = false;
  uint32_t emitters = 0;
  uint32_t materials = 0;
  uint32_t textures = 0;
  uint64_t textureBytes = 0;       // all mip levels
  uint64_t geometryBytes = 0;      // vertex attributes + indices
  Aabb bounds;
  RepairCounters repairs;
};

// Default aspect ratio for visibility counts: the thesis' 1920x1080.
inline constexpr float kDefaultAspect = 16.0f / 9.0f;

SceneStats stats(const Scene& scene, float aspect = kDefaultAspect);

nlohmann::json toJson(const SceneStats& stats);
nlohmann::json toJson(const RepairCounters& repairs);
nlohmann::json toJson(const Camera& camera);

// A stable hash of the cooked content (geometry, materials, textures, lights, camera, post), as 16
// hex digits: equal scenes hash equal on every machine.
std::string contentHash(const Scene& scene);

}  // namespace fgb::scene
