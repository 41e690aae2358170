// Cooking: vertex cache and fetch optimisation per mesh, its cluster LOD DAG, bounds, default material.
#include <fgb/scene/cook.hpp>

#include <fgb/scene/geometry.hpp>

#include "cluster_lod.hpp"

#include <meshoptimizer.h>

#include <vector>

namespace fgb::scene {
namespace {

template <typename T>
void remapRange(std::vector<T>& attribute, uint32_t first, uint32_t count, const std::vector<unsigned int>& remap) {
  std::vector<T> reordered(count);
  meshopt_remapVertexBuffer(reordered.data(), attribute.data() + first, count, sizeof(T), remap.data());
  std::copy(reordered.begin(), reordered.end(), attribute.begin() + first);
}

void optimizeMesh(Scene& scene, const Mesh& mesh) {
  if (mesh.indexCount == 0) return;
  unsigned int* indices = scene.indices.data() + mesh.firstIndex;
  meshopt_optimizeVertexCache(indices, indices, mesh.indexCount, mesh.vertexCount);
  // Reorder vertices into first-use order so the GPU streams them linearly. The mesh was
  // compacted by repairMesh, so every vertex is referenced and the count does not change.
  std::vector<unsigned int> remap(mesh.vertexCount);
  const size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), indices, mesh.indexCount, mesh.vertexCount);
  if (used != mesh.vertexCount) return;  // unreferenced vertices: keep the order rather than drop data
  meshopt_remapIndexBuffer(indices, indices, mesh.indexCount, remap.data());
  remapRange(scene.positions, mesh.firstVertex, mesh.vertexCount, remap);
  remapRange(scene.normals, mesh.firstVertex, mesh.vertexCount, remap);
  remapRange(scene.tangents, mesh.firstVertex, mesh.vertexCount, remap);
  remapRange(scene.uv0, mesh.firstVertex, mesh.vertexCount, remap);
}

}  // namespace

void cookScene(Scene& scene) {
  scene.clusters.clear();
  scene.clusterTriangles.clear();
  scene.clusterVertices.clear();
  for (Mesh& mesh : scene.meshes) {
    optimizeMesh(scene, mesh);
    detail::buildClusterLod(scene, mesh);
  }
  if (scene.materials.empty() && !scene.instances.empty()) {
    Material fallback;
    fallback.name = "default";
    fallback.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    fallback.metallicFactor = 0.0f;
    fallback.roughnessFactor = 0.7f;
    scene.materials.push_back(fallback);
  }
  updateBounds(scene);
}

}  // namespace fgb::scene
