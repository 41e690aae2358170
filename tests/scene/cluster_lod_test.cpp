// The cooked cluster LOD DAG (cluster_lod.cpp): errors and bounds monotonic up the DAG, every
// threshold's cut covers each mesh exactly once (no crack, no overlap), and the bytes it costs.
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fgb/scene/cook.hpp>
#include <fgb/scene/generators.hpp>
#include <map>
#include <set>
#include <vector>

using namespace fgb::scene;

namespace {

// A small atrium: every mesh kind of the full one, a tenth of the triangles.
const Scene& smallAtrium() {
  static const Scene scene = [] {
    Scene s = generate("atrium", resolveGeneratorParams({"atrium", {{"scale", 0.1}, {"texture_size", 16}}},
                                                        Knobs::parse({}), "test.json"));
    cookScene(s);
    return s;
  }();
  return scene;
}

// A cluster's triangles as mesh-local vertex triples.
std::vector<std::array<uint32_t, 3>> trianglesOf(const Scene& s, const Cluster& cluster) {
  std::vector<std::array<uint32_t, 3>> result;
  for (uint32_t t = 0; t < cluster.triangleCount; ++t) {
    const uint32_t packed = s.clusterTriangles[cluster.firstTriangle + t];
    std::array<uint32_t, 3> tri{};
    for (uint32_t k = 0; k < 3; ++k) tri[k] = s.clusterVertices[cluster.firstVertex + clusterTriangleCorner(packed, k)];
    result.push_back(tri);
  }
  return result;
}

// The boundary chain of a set of triangles, with vertices welded by position: per undirected
// edge, its uses a->b minus its uses b->a (a < b). Inside a consistently wound surface they
// cancel; what is left is the surface's border. A crack between two parts of a cut adds edges that
// do not cancel, and an overlap adds the border of the piece drawn twice: either changes the chain.
std::map<std::pair<uint32_t, uint32_t>, int> boundaryChain(const std::vector<std::array<uint32_t, 3>>& triangles,
                                                           const std::vector<uint32_t>& weld) {
  std::map<std::pair<uint32_t, uint32_t>, int> chain;
  for (const auto& tri : triangles)
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t a = weld[tri[k]], b = weld[tri[(k + 1) % 3]];
      if (a == b) continue;
      chain[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  std::erase_if(chain, [](const auto& entry) { return entry.second == 0; });
  return chain;
}

std::vector<uint32_t> weldByPosition(const Scene& s, const Mesh& mesh) {
  std::vector<uint32_t> weld(mesh.vertexCount);
  meshopt_generateVertexRemap(weld.data(), nullptr, mesh.vertexCount, &s.positions[mesh.firstVertex].x,
                              mesh.vertexCount, sizeof(glm::vec3));
  return weld;
}

std::vector<std::array<uint32_t, 3>> cutOf(const Scene& s, const Mesh& mesh, float threshold) {
  std::vector<std::array<uint32_t, 3>> triangles;
  for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c)
    if (inLodCut(s.clusters[c], threshold)) {
      const auto tris = trianglesOf(s, s.clusters[c]);
      triangles.insert(triangles.end(), tris.begin(), tris.end());
    }
  return triangles;
}

}  // namespace

// A cluster's parent error is at least its own (and above 0), and its parent's sphere holds its own: the projected
// error can only grow up the DAG, so one threshold cuts it once. Each group replaces its members
// with clusters made from them: the members' parent (bounds, error) is the made clusters' own.
TEST(ClusterLod, ErrorsAndBoundsGrowUpTheDag) {
  const Scene& s = smallAtrium();
  uint32_t above = 0;
  for (const Mesh& mesh : s.meshes) {
    std::set<std::tuple<float, float, float, float, float>> groupsMade, groupsReplaced;
    for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c) {
      const Cluster& cluster = s.clusters[c];
      const bool base = c < mesh.firstCluster + mesh.baseClusterCount;
      EXPECT_EQ(cluster.lodLevel == 0, base) << mesh.name;
      EXPECT_EQ(cluster.lodError == 0.0f, base) << mesh.name;
      // Flat parts simplify with no error: equal errors up the DAG are fine, but never 0 above
      // level 0 (threshold 0 is the mesh itself).
      EXPECT_GE(cluster.parentError, cluster.lodError) << mesh.name << " cluster " << c;
      EXPECT_GT(cluster.parentError, 0.0f) << mesh.name << " cluster " << c;
      EXPECT_LE(glm::length(cluster.parentCenter - cluster.lodCenter) + cluster.lodRadius,
                cluster.parentRadius * 1.0001f + 1e-6f)
          << mesh.name << " cluster " << c;
      const auto group = [](glm::vec3 center, float radius, float error) {
        return std::tuple(center.x, center.y, center.z, radius, error);
      };
      if (!base) groupsMade.insert(group(cluster.lodCenter, cluster.lodRadius, cluster.lodError));
      if (cluster.parentError < kLodRootError)
        groupsReplaced.insert(group(cluster.parentCenter, cluster.parentRadius, cluster.parentError));
      above += base ? 0 : 1;
    }
    EXPECT_EQ(groupsMade, groupsReplaced) << mesh.name;
  }
  EXPECT_GT(above, 0u);
}

// Shading interpolates a triangle's corner normals, so a simplified triangle across a curved part
// moves highlights even where its positions are exact. A simplified cluster's error therefore
// covers half its triangles' normal spread (largest edge times largest angle between two corner
// normals, in radians; the group's spread is at least any of its clusters'). Some cluster of the
// atrium's vases and columns needs it: their positional error and radius floor are smaller.
TEST(ClusterLod, ErrorsCoverTheNormalsSpread) {
  const Scene& s = smallAtrium();
  uint32_t raisedByNormals = 0;
  for (const Mesh& mesh : s.meshes)
    for (uint32_t c = mesh.firstCluster + mesh.baseClusterCount; c < mesh.firstCluster + mesh.clusterCount; ++c) {
      const Cluster& cluster = s.clusters[c];
      float spread = 0.0f;
      for (const auto& tri : trianglesOf(s, cluster)) {
        float angle = 0.0f;
        float edge = 0.0f;
        for (uint32_t k = 0; k < 3; ++k) {
          const uint32_t a = mesh.firstVertex + tri[k];
          const uint32_t b = mesh.firstVertex + tri[(k + 1) % 3];
          const float cosine = glm::dot(glm::normalize(s.normals[a]), glm::normalize(s.normals[b]));
          angle = std::max(angle, std::acos(std::clamp(cosine, -1.0f, 1.0f)));
          edge = std::max(edge, glm::length(s.positions[a] - s.positions[b]));
        }
        spread = std::max(spread, angle * edge);
      }
      EXPECT_GE(cluster.lodError, 0.5f * spread * 0.999f) << mesh.name << " cluster " << c;
      if (0.5f * spread > 0.02f * cluster.lodRadius) ++raisedByNormals;
    }
  EXPECT_GT(raisedByNormals, 0u) << "no cluster's error was raised by its normals: the test checks nothing";
}

// At every threshold, the cut's clusters cover each mesh exactly once: its boundary chain is the
// mesh's own (no crack, no overlap) and it never has more triangles than the mesh. Threshold 0 is
// the mesh itself; thresholds between and at the DAG's errors, and above all of them, are tried.
TEST(ClusterLod, EveryThresholdCutsEachMeshOnce) {
  const Scene& s = smallAtrium();
  uint64_t fullTriangles = 0, coarsestTriangles = 0;
  for (const Mesh& mesh : s.meshes) {
    const std::vector<uint32_t> weld = weldByPosition(s, mesh);
    std::vector<std::array<uint32_t, 3>> full;
    for (uint32_t i = 0; i < mesh.indexCount; i += 3)
      full.push_back(
          {s.indices[mesh.firstIndex + i], s.indices[mesh.firstIndex + i + 1], s.indices[mesh.firstIndex + i + 2]});
    const auto fullChain = boundaryChain(full, weld);
    std::set<float> thresholds{0.0f, 1e30f};
    for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c) {
      const float error = s.clusters[c].lodError;
      thresholds.insert(error);
      thresholds.insert(error * 1.5f);
    }
    for (float threshold : thresholds) {
      const auto cut = cutOf(s, mesh, threshold);
      ASSERT_LE(cut.size(), full.size()) << mesh.name << " at " << threshold;
      ASSERT_EQ(boundaryChain(cut, weld), fullChain) << mesh.name << " at " << threshold;
      if (threshold == 0.0f) {
        ASSERT_EQ(cut.size(), full.size()) << mesh.name;
      }
    }
    fullTriangles += full.size();
    coarsestTriangles += cutOf(s, mesh, 1e30f).size();
  }
  // The DAG simplifies: the coarsest cut of the whole scene is a small part of it.
  EXPECT_LT(double(coarsestTriangles), 0.25 * double(fullTriangles));
}

// All levels together cost at most 2.2 times the geometry cooked without LOD: the vertex streams
// and index buffer, and level 0 as a plain cluster list (48 bytes per cluster before the LOD
// fields, its packed triangles and vertex lists).
TEST(ClusterLod, AllLevelsStayWithinTheByteBudget) {
  const Scene& s = smallAtrium();
  const uint64_t vertexBytes = s.positions.size() * (sizeof(glm::vec3) * 2 + sizeof(glm::vec4) + sizeof(glm::vec2));
  const uint64_t indexBytes = s.indices.size() * 4;
  uint64_t baseBytes = vertexBytes + indexBytes;
  for (const Mesh& mesh : s.meshes)
    for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.baseClusterCount; ++c)
      baseBytes += 48 + 4 * (s.clusters[c].triangleCount + s.clusters[c].vertexCount);
  const uint64_t lodBytes = vertexBytes + indexBytes + s.clusters.size() * sizeof(Cluster) +
                            4 * (s.clusterTriangles.size() + s.clusterVertices.size());
  EXPECT_LE(double(lodBytes), 2.2 * double(baseBytes)) << lodBytes << " bytes against " << baseBytes;
}
