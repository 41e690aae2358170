// Cooking: vertex cache and fetch optimisation per mesh, bounds, default material.
#include <fgb/scene/cook.hpp>

#include <fgb/scene/geometry.hpp>

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

// Splits the mesh (after optimizeMesh: its final index order) into clusters of at most
// kClusterMaxTriangles triangles with bounding spheres and normal cones.
void buildClusters(Scene& scene, Mesh& mesh) {
  mesh.firstCluster = static_cast<uint32_t>(scene.clusters.size());
  mesh.clusterCount = 0;
  if (mesh.indexCount == 0) return;
  const unsigned int* indices = scene.indices.data() + mesh.firstIndex;
  const float* positions = &scene.positions[mesh.firstVertex].x;
  const size_t maxClusters = meshopt_buildMeshletsBound(mesh.indexCount, kClusterMaxVertices, kClusterMaxTriangles);
  std::vector<meshopt_Meshlet> meshlets(maxClusters);
  std::vector<unsigned int> meshletVertices(maxClusters * kClusterMaxVertices);
  std::vector<unsigned char> meshletTriangles(maxClusters * kClusterMaxTriangles * 3);
  // Cone weight 0.25: a little looser spatial grouping for cones that cull more often.
  const size_t count = meshopt_buildMeshlets(meshlets.data(), meshletVertices.data(), meshletTriangles.data(), indices,
                                             mesh.indexCount, positions, mesh.vertexCount, sizeof(glm::vec3),
                                             kClusterMaxVertices, kClusterMaxTriangles, 0.25f);
  for (size_t i = 0; i < count; ++i) {
    const meshopt_Meshlet& m = meshlets[i];
    const meshopt_Bounds bounds =
        meshopt_computeMeshletBounds(&meshletVertices[m.vertex_offset], &meshletTriangles[m.triangle_offset],
                                     m.triangle_count, positions, mesh.vertexCount, sizeof(glm::vec3));
    Cluster cluster;
    cluster.center = {bounds.center[0], bounds.center[1], bounds.center[2]};
    cluster.radius = bounds.radius;
    cluster.coneAxis = {bounds.cone_axis[0], bounds.cone_axis[1], bounds.cone_axis[2]};
    cluster.coneCutoff = bounds.cone_cutoff;
    cluster.firstTriangle = static_cast<uint32_t>(scene.clusterTriangles.size());
    cluster.triangleCount = m.triangle_count;
    cluster.firstVertex = static_cast<uint32_t>(scene.clusterVertices.size());
    cluster.vertexCount = m.vertex_count;
    // meshoptimizer's own form: 8-bit indices into the meshlet's vertex list, in its triangle order.
    const unsigned char* local = &meshletTriangles[m.triangle_offset];
    for (uint32_t t = 0; t < m.triangle_count; ++t)
      scene.clusterTriangles.push_back(packClusterTriangle(local[3 * t], local[3 * t + 1], local[3 * t + 2]));
    scene.clusterVertices.insert(scene.clusterVertices.end(), meshletVertices.begin() + m.vertex_offset,
                                 meshletVertices.begin() + m.vertex_offset + m.vertex_count);
    scene.clusters.push_back(cluster);
  }
  mesh.clusterCount = static_cast<uint32_t>(count);
}

}  // namespace

void cookScene(Scene& scene) {
  scene.clusters.clear();
  scene.clusterTriangles.clear();
  scene.clusterVertices.clear();
  for (Mesh& mesh : scene.meshes) {
    optimizeMesh(scene, mesh);
    buildClusters(scene, mesh);
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
