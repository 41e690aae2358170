// Scene statistics and JSON output.
#include <fgb/scene/stats.hpp>

#include <fgb/scene/frustum.hpp>

#include "serialize.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

#include <cstdio>

namespace fgb::scene {

SceneStats stats(const Scene& scene, float aspect) {
  SceneStats s;
  s.instances = static_cast<uint32_t>(scene.instances.size());
  s.meshes = static_cast<uint32_t>(scene.meshes.size());
  for (const Instance& instance : scene.instances) s.triangles += scene.meshes[instance.mesh].triangleCount();
  for (const Mesh& mesh : scene.meshes) s.uniqueTriangles += mesh.triangleCount();
  const Visibility visible = countVisible(scene, scene.camera, aspect);
  s.instancesVisible = visible.instances;
  s.trianglesVisible = visible.triangles;
  s.vertices = scene.positions.size();
  s.lights = static_cast<uint32_t>(scene.lights.size());
  s.directionalLight = scene.sun.enabled;
  s.emitters = static_cast<uint32_t>(scene.emitters.size());
  s.materials = static_cast<uint32_t>(scene.materials.size());
  s.textures = static_cast<uint32_t>(scene.textures.size());
  for (const Texture& texture : scene.textures) s.textureBytes += texture.data.size();
  s.geometryBytes = scene.positions.size() * sizeof(glm::vec3) + scene.normals.size() * sizeof(glm::vec3) +
                    scene.tangents.size() * sizeof(glm::vec4) + scene.uv0.size() * sizeof(glm::vec2) +
                    scene.indices.size() * sizeof(uint32_t);
  s.bounds = scene.bounds();
  s.repairs = scene.repairs;
  return s;
}

namespace {

nlohmann::json vec3(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

}  // namespace

nlohmann::json toJson(const RepairCounters& r) {
  return {{"total", r.total()},
          {"non_finite_positions", r.nonFinitePositions},
          {"non_finite_triangles", r.nonFiniteTriangles},
          {"non_finite_normals", r.nonFiniteNormals},
          {"zero_normals", r.zeroNormals},
          {"non_finite_tangents", r.nonFiniteTangents},
          {"zero_tangents", r.zeroTangents},
          {"non_finite_uvs", r.nonFiniteUvs},
          {"degenerate_triangles", r.degenerateTriangles},
          {"zero_area_triangles", r.zeroAreaTriangles},
          {"non_triangle_primitives", r.nonTrianglePrimitives},
          {"generated_normals", r.generatedNormals},
          {"generated_tangents", r.generatedTangents},
          {"missing_textures", r.missingTextures},
          {"empty_meshes", r.emptyMeshes}};
}

nlohmann::json toJson(const Camera& c) {
  return {{"position", vec3(c.position)}, {"target", vec3(c.target)}, {"up", vec3(c.up)},
          {"fov_deg", c.verticalFovDeg},   {"near", c.nearPlane},
          // JSON has no infinity: an infinite far plane is written as the knob spells it.
          {"far", std::isinf(c.farPlane) ? nlohmann::json("inf") : nlohmann::json(c.farPlane)}};
}

nlohmann::json toJson(const SceneStats& s) {
  nlohmann::json bounds = nullptr;
  if (!s.bounds.isEmpty()) bounds = {{"min", vec3(s.bounds.min)}, {"max", vec3(s.bounds.max)}};
  return {{"instances", s.instances},
          {"instances_visible", s.instancesVisible},
          {"meshes", s.meshes},
          {"triangles", s.triangles},
          {"triangles_visible", s.trianglesVisible},
          {"unique_triangles", s.uniqueTriangles},
          {"vertices", s.vertices},
          {"lights", s.lights},
          {"directional_light", s.directionalLight},
          {"emitters", s.emitters},
          {"materials", s.materials},
          {"textures", s.textures},
          {"texture_bytes", s.textureBytes},
          {"geometry_bytes", s.geometryBytes},
          {"bounds", bounds},
          {"repairs", toJson(s.repairs)}};
}

std::string contentHash(const Scene& scene) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(detail::hashScene(scene)));
  return text;
}

}  // namespace fgb::scene
