// Building scenes: one mesh's raw data, its repair (hostile inputs never reach the GPU), tangent
// generation, and appending meshes/instances/whole scenes into a Scene. Used by the generators and
// by the model importer (fgb_import), so every source gets the same repairs and counters.
#pragma once

#include <fgb/scene/scene.hpp>

#include <string>
#include <vector>

namespace fgb::scene {

// One mesh before it is appended to a Scene's shared arrays. normals/tangents/uv0 may be empty
// (they are then generated); when present they have one entry per position.
struct MeshData {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uv0;
  std::vector<uint32_t> indices;  // triangle list, mesh-local

  size_t triangleCount() const { return indices.size() / 3; }
};

// Makes a mesh render-ready and counts every change in `repairs`:
//   - an index >= positions.size() throws fgb::InputError "<context>: mesh '<name>': ..." (a broken
//     file, not something to guess about);
//   - triangles using a NaN/Inf position, repeating an index, or with zero area are removed;
//   - NaN/Inf UVs are zeroed; missing, NaN/Inf or zero normals and tangents are recomputed.
// Unreferenced vertices are kept (cheap; the cooker's fetch optimisation drops them).
void repairMesh(MeshData& mesh, RepairCounters& repairs, const std::string& context);

// Area-weighted vertex normals for the vertices flagged in `recompute` (all when empty).
void computeNormals(MeshData& mesh, const std::vector<bool>& recompute = {});
// Per-vertex tangents from UV derivatives (Lengyel), orthonormalised against the normal; vertices
// without usable UVs get any unit vector perpendicular to the normal (w = +1).
void computeTangents(MeshData& mesh, const std::vector<bool>& recompute = {});

// Appends a (repaired) mesh to the scene's shared arrays; returns its index. Empty meshes are
// appended too (callers usually skip them and count RepairCounters::emptyMeshes).
uint32_t appendMesh(Scene& scene, MeshData&& mesh);
// Appends a texture or a material, returning its index (what materials and instances refer to).
int32_t addTexture(Scene& scene, Texture&& texture);
uint32_t addMaterial(Scene& scene, Material material);
// Adds an instance, computing its world bounds from the mesh's local bounds.
uint32_t addInstance(Scene& scene, uint32_t mesh, uint32_t material, const glm::dmat4& transform);
// Recomputes every mesh's local bounds and every instance's world bounds.
void updateBounds(Scene& scene);

// Moves `part` into `into`, placing it with `placement`: meshes, materials and textures are
// renumbered, instances, lights and emitters transformed, repairs and warnings accumulated.
// Camera, sun and post settings of `part` are taken only where `into` has none.
void mergeScene(Scene& into, Scene&& part, const glm::dmat4& placement);

}  // namespace fgb::scene
