// The cluster LOD DAG (Karis 2021) with meshoptimizer 0.18, which has no cluster grouping, no
// sparse simplification and no absolute errors: the grouping is ours (shared edges, then space),
// each group's vertices are copied into a compact buffer before simplifying (0.18 costs time in the
// size of the vertex buffer it is given), and its relative error is scaled by that buffer's extent.
#include "cluster_lod.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fgb::scene::detail {
namespace {

constexpr uint32_t kGroupSize = 8;      // clusters merged into one group (~1024 triangles)
constexpr uint32_t kSmallGroup = 3;     // groups smaller than this are merged with spatial neighbours
constexpr float kMinReduction = 0.85f;  // a simplification keeping more triangles than this is stuck
constexpr uint32_t kMaxLevels = 24;     // a bound on the loop; the DAG stops earlier when nothing simplifies
// A group's error is at least this fraction of its sphere's radius. Flat parts simplify with no
// error at all, down to a few triangles the size of a wall, which the compute raster's
// large-triangle path draws more slowly than many small ones (lavapipe, atrium: 10x the large
// triangles, Visibility Raster 1.7x); the floor keeps a group's triangles near pixel size on screen
// at the thresholds used. It grows with the sphere, so errors stay monotonic up the DAG.
constexpr float kErrorPerRadius = 0.02f;
// A group's error is at least this times its simplified triangles' normal spread (normalSpread).
// Measured on the atrium at 640x360, render.lod_error=1 against full detail (LDR-FLIP mean /
// triangles rasterised, full detail 469 k): positions alone 0.0188 / 262 k, errors on the vases'
// and capitals' highlights; weight 0.5: 0.0034 / 349 k; 1: 0.0022 / 375 k; 2: 0.0017 / 386 k.
constexpr float kNormalWeight = 0.5f;
constexpr float kConeWeight = 0.25f;    // meshopt_buildMeshlets: a little looser grouping for cones that cull

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// The smallest-box-centred sphere holding every sphere given (not minimal, but it contains them,
// which is what keeps the projected errors monotonic up the DAG).
Sphere enclosing(std::span<const Sphere> spheres) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Sphere& s : spheres) {
    lo = glm::min(lo, s.center - s.radius);
    hi = glm::max(hi, s.center + s.radius);
  }
  Sphere result{(lo + hi) * 0.5f, 0.0f};
  for (const Sphere& s : spheres)
    result.radius = std::max(result.radius, glm::length(s.center - result.center) + s.radius);
  return result;
}

// One mesh being cooked: its positions, the position-welded id of each vertex (vertices that share
// a position share it: UV seams and hard normals do not cut the surface for grouping), and the
// smallest error a group may have (so that threshold 0 is exactly level 0).
struct MeshLod {
  Scene& scene;
  Mesh& mesh;
  const glm::vec3* positions;
  std::vector<uint32_t> weld;
  float minError;
  std::vector<uint32_t> localOf;  // scratch, mesh vertex -> compact group vertex (~0u: none)
};

// The mesh-local corners of a cluster's triangles, appended to `out`.
void appendTriangles(const Scene& scene, const Cluster& cluster, std::vector<uint32_t>& out) {
  for (uint32_t t = 0; t < cluster.triangleCount; ++t) {
    const uint32_t packed = scene.clusterTriangles[cluster.firstTriangle + t];
    for (uint32_t corner = 0; corner < 3; ++corner)
      out.push_back(scene.clusterVertices[cluster.firstVertex + clusterTriangleCorner(packed, corner)]);
  }
}

// Splits `indices` (into `positions`, whose vertex i is mesh vertex toMesh[i], or i itself when
// toMesh is empty) into clusters appended to the scene; returns their indices. LOD fields are left
// to the caller.
std::vector<uint32_t> emitClusters(Scene& scene, std::span<const uint32_t> indices,
                                   std::span<const glm::vec3> positions, std::span<const uint32_t> toMesh) {
  const size_t maxClusters = meshopt_buildMeshletsBound(indices.size(), kClusterMaxVertices, kClusterMaxTriangles);
  std::vector<meshopt_Meshlet> meshlets(maxClusters);
  std::vector<unsigned int> meshletVertices(maxClusters * kClusterMaxVertices);
  std::vector<unsigned char> meshletTriangles(maxClusters * kClusterMaxTriangles * 3);
  const size_t count = meshopt_buildMeshlets(meshlets.data(), meshletVertices.data(), meshletTriangles.data(),
                                             indices.data(), indices.size(), &positions[0].x, positions.size(),
                                             sizeof(glm::vec3), kClusterMaxVertices, kClusterMaxTriangles, kConeWeight);
  std::vector<uint32_t> made;
  for (size_t i = 0; i < count; ++i) {
    const meshopt_Meshlet& m = meshlets[i];
    const meshopt_Bounds bounds =
        meshopt_computeMeshletBounds(&meshletVertices[m.vertex_offset], &meshletTriangles[m.triangle_offset],
                                     m.triangle_count, &positions[0].x, positions.size(), sizeof(glm::vec3));
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
    for (uint32_t v = 0; v < m.vertex_count; ++v) {
      const uint32_t vertex = meshletVertices[m.vertex_offset + v];
      scene.clusterVertices.push_back(toMesh.empty() ? vertex : toMesh[vertex]);
    }
    made.push_back(static_cast<uint32_t>(scene.clusters.size()));
    scene.clusters.push_back(cluster);
  }
  return made;
}

// 30-bit Morton code of a point in the box [lo, lo + size].
uint32_t morton(glm::vec3 p, glm::vec3 lo, glm::vec3 size) {
  const auto spread = [](uint32_t v) {
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    return (v | (v << 2)) & 0x09249249u;
  };
  const glm::vec3 unit = glm::clamp((p - lo) / glm::max(size, glm::vec3(1e-20f)), 0.0f, 1.0f);
  const glm::uvec3 q(unit * 1023.0f);
  return spread(q.x) << 2 | spread(q.y) << 1 | spread(q.z);
}

// Pool positions in the Morton order of their LOD spheres' centres.
std::vector<uint32_t> spatialOrder(const Scene& scene, std::span<const uint32_t> pool) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (uint32_t c : pool) {
    lo = glm::min(lo, scene.clusters[c].lodCenter);
    hi = glm::max(hi, scene.clusters[c].lodCenter);
  }
  std::vector<std::pair<uint32_t, uint32_t>> keyed;
  for (uint32_t i = 0; i < pool.size(); ++i)
    keyed.emplace_back(morton(scene.clusters[pool[i]].lodCenter, lo, hi - lo), i);
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> order;
  for (const auto& [key, i] : keyed) order.push_back(i);
  return order;
}

// For each pool position, its neighbours (pool positions) and how many welded edges they share.
std::vector<std::vector<std::pair<uint32_t, uint32_t>>> sharedEdges(const MeshLod& lod,
                                                                    std::span<const uint32_t> pool) {
  std::vector<std::pair<uint64_t, uint32_t>> edges;  // welded edge key, pool position
  std::vector<uint32_t> corners;
  for (uint32_t i = 0; i < pool.size(); ++i) {
    corners.clear();
    appendTriangles(lod.scene, lod.scene.clusters[pool[i]], corners);
    for (size_t t = 0; t < corners.size(); t += 3)
      for (uint32_t e = 0; e < 3; ++e) {
        const uint32_t a = lod.weld[corners[t + e]], b = lod.weld[corners[t + (e + 1) % 3]];
        if (a != b) edges.emplace_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b), i);
      }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<uint32_t, uint32_t>> pairs;  // (pool position, neighbour), once per shared edge
  for (size_t begin = 0, end = 0; begin < edges.size(); begin = end) {
    while (end < edges.size() && edges[end].first == edges[begin].first) ++end;
    for (size_t i = begin; i < end; ++i)
      for (size_t j = begin; j < end; ++j)
        if (edges[i].second != edges[j].second) pairs.emplace_back(edges[i].second, edges[j].second);
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> adjacency(pool.size());
  for (size_t begin = 0, end = 0; begin < pairs.size(); begin = end) {
    while (end < pairs.size() && pairs[end] == pairs[begin]) ++end;
    adjacency[pairs[begin].first].emplace_back(pairs[begin].second, uint32_t(end - begin));
  }
  return adjacency;
}

// Groups of up to kGroupSize pool clusters (as scene cluster indices): grown from seeds in spatial
// order by the neighbour sharing the most edges with the group; groups left small (islands, the
// mesh's loose pieces) are then merged with the next small groups in spatial order.
std::vector<std::vector<uint32_t>> groupClusters(const MeshLod& lod, std::span<const uint32_t> pool) {
  const auto adjacency = sharedEdges(lod, pool);
  const auto order = spatialOrder(lod.scene, pool);
  std::vector<bool> grouped(pool.size(), false);
  std::vector<uint32_t> weight(pool.size(), 0);  // shared edges with the group being grown
  std::vector<std::vector<uint32_t>> groups, small;
  for (uint32_t seed : order) {
    if (grouped[seed]) continue;
    std::vector<uint32_t> members{seed}, candidates;
    grouped[seed] = true;
    const auto take = [&](uint32_t member) {
      for (const auto& [neighbour, shared] : adjacency[member]) {
        if (grouped[neighbour]) continue;
        if (weight[neighbour] == 0) candidates.push_back(neighbour);
        weight[neighbour] += shared;
      }
    };
    take(seed);
    while (members.size() < kGroupSize) {
      uint32_t best = UINT32_MAX;
      for (uint32_t c : candidates)
        if (!grouped[c] && (best == UINT32_MAX || weight[c] > weight[best])) best = c;
      if (best == UINT32_MAX) break;
      grouped[best] = true;
      members.push_back(best);
      take(best);
    }
    for (uint32_t c : candidates) weight[c] = 0;
    (members.size() < kSmallGroup ? small : groups).push_back(std::move(members));
  }
  // Small groups come in seed (spatial) order: merge runs of them.
  std::vector<uint32_t> merged;
  for (const auto& members : small) {
    if (merged.size() + members.size() > kGroupSize) groups.push_back(std::exchange(merged, {}));
    merged.insert(merged.end(), members.begin(), members.end());
  }
  if (!merged.empty()) groups.push_back(std::move(merged));
  for (auto& members : groups)
    for (uint32_t& member : members) member = pool[member];
  return groups;
}

// A group merged and simplified: its triangles in a compact vertex buffer.
struct SimplifiedGroup {
  std::vector<uint32_t> indices;  // into positions
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> toMesh;  // compact vertex -> mesh vertex
  float error = 0.0f;            // mesh-local distance
  float normalError = 0.0f;      // normalSpread: mesh-local distance times radians
};

// How far the simplified triangles stretch their corners' normals: the largest edge times the
// largest angle between two of its triangle's corner normals (radians). Shading interpolates the
// normals over each triangle, so a coarse triangle across a curved, shiny part (a vase, a
// capital) moves its highlights even where its positions stay within the simplifier's error.
float normalSpread(const MeshLod& lod, const SimplifiedGroup& group) {
  const auto normal = [&](uint32_t local) {
    const glm::vec3 n = lod.scene.normals[lod.mesh.firstVertex + group.toMesh[local]];
    const float length = glm::length(n);
    return length > 0.0f ? n / length : n;
  };
  float spread = 0.0f;
  if (lod.scene.normals.size() < size_t{lod.mesh.firstVertex} + lod.mesh.vertexCount) return spread;
  for (size_t t = 0; t + 2 < group.indices.size(); t += 3) {
    float angle = 0.0f, edge = 0.0f;
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = group.indices[t + e], b = group.indices[t + (e + 1) % 3];
      angle = std::max(angle, std::acos(std::clamp(glm::dot(normal(a), normal(b)), -1.0f, 1.0f)));
      edge = std::max(edge, glm::length(group.positions[a] - group.positions[b]));
    }
    spread = std::max(spread, angle * edge);
  }
  return spread;
}

// Merges the group's triangles and simplifies them to about half with the outer border locked.
// Vertices that share a position with another group vertex (UV seams, hard normals) are locked too:
// 0.18 has no attribute-aware simplification and no lock list, so the copies the simplifier sees
// are nudged apart by an ulp each, which makes every such seam an open border it keeps. Empty when
// the group does not simplify enough.
SimplifiedGroup simplifyGroup(MeshLod& lod, std::span<const uint32_t> members) {
  std::vector<uint32_t> meshIndices;
  for (uint32_t c : members) appendTriangles(lod.scene, lod.scene.clusters[c], meshIndices);
  SimplifiedGroup group;
  std::vector<glm::vec3> nudged;
  std::unordered_map<uint32_t, uint32_t> copiesOfWeld;
  std::vector<uint32_t> localIndices;
  for (uint32_t vertex : meshIndices) {
    if (lod.localOf[vertex] == UINT32_MAX) {
      lod.localOf[vertex] = static_cast<uint32_t>(group.positions.size());
      group.toMesh.push_back(vertex);
      group.positions.push_back(lod.positions[vertex]);
      glm::vec3 p = lod.positions[vertex];
      for (uint32_t k = copiesOfWeld[lod.weld[vertex]]++; k > 0; --k)
        p.x = std::nextafter(p.x, std::numeric_limits<float>::infinity());
      nudged.push_back(p);
    }
    localIndices.push_back(lod.localOf[vertex]);
  }
  for (uint32_t vertex : group.toMesh) lod.localOf[vertex] = UINT32_MAX;

  const size_t triangles = localIndices.size() / 3;
  if (triangles == 0) return {};
  group.indices.assign(localIndices.size(), 0u);
  float relativeError = 0.0f;
  // Target error 1: as far as the triangle target needs (the error is what it measures).
  const size_t kept =
      meshopt_simplify(group.indices.data(), localIndices.data(), localIndices.size(), &nudged[0].x, nudged.size(),
                       sizeof(glm::vec3), (triangles / 2) * 3, 1.0f, meshopt_SimplifyLockBorder, &relativeError);
  if (kept == 0 || float(kept / 3) > kMinReduction * float(triangles)) return {};
  group.indices.resize(kept);
  group.error = relativeError * meshopt_simplifyScale(&nudged[0].x, nudged.size(), sizeof(glm::vec3));
  group.normalError = normalSpread(lod, group);
  return group;
}

// One level: groups the pool, simplifies each group into clusters of the next level. Returns the
// next level's pool: the new clusters and the clusters of groups that did not simplify.
std::vector<uint32_t> buildLevel(MeshLod& lod, std::span<const uint32_t> pool) {
  std::vector<uint32_t> next;
  for (const auto& members : groupClusters(lod, pool)) {
    SimplifiedGroup simplified = members.size() > 1 ? simplifyGroup(lod, members) : SimplifiedGroup{};
    if (simplified.indices.empty()) {
      next.insert(next.end(), members.begin(), members.end());
      continue;
    }
    std::vector<Sphere> spheres;
    float error = std::max({simplified.error, kNormalWeight * simplified.normalError, lod.minError});
    uint32_t level = 0;
    for (uint32_t c : members) {
      const Cluster& member = lod.scene.clusters[c];
      spheres.push_back({member.lodCenter, member.lodRadius});
      error = std::max(error, member.lodError);  // monotonic: at least every member's
      level = std::max(level, member.lodLevel + 1);
    }
    const Sphere bounds = enclosing(spheres);
    error = std::max(error, kErrorPerRadius * bounds.radius);
    for (uint32_t c : members) {
      Cluster& member = lod.scene.clusters[c];
      member.parentCenter = bounds.center;
      member.parentRadius = bounds.radius;
      member.parentError = error;
    }
    for (uint32_t c : emitClusters(lod.scene, simplified.indices, simplified.positions, simplified.toMesh)) {
      Cluster& made = lod.scene.clusters[c];
      made.lodCenter = made.parentCenter = bounds.center;
      made.lodRadius = made.parentRadius = bounds.radius;
      made.lodError = error;
      made.lodLevel = level;
      next.push_back(c);
    }
  }
  return next;
}

}  // namespace

void buildClusterLod(Scene& scene, Mesh& mesh) {
  mesh.firstCluster = static_cast<uint32_t>(scene.clusters.size());
  mesh.clusterCount = mesh.baseClusterCount = 0;
  if (mesh.indexCount == 0) return;
  const std::span<const glm::vec3> positions(scene.positions.data() + mesh.firstVertex, mesh.vertexCount);
  const std::span<const uint32_t> indices(scene.indices.data() + mesh.firstIndex, mesh.indexCount);
  std::vector<uint32_t> pool = emitClusters(scene, indices, positions, {});
  for (uint32_t c : pool) {
    Cluster& cluster = scene.clusters[c];
    cluster.lodCenter = cluster.parentCenter = cluster.center;
    cluster.lodRadius = cluster.parentRadius = cluster.radius;
  }
  mesh.baseClusterCount = static_cast<uint32_t>(pool.size());

  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 extent = hi - lo;
  MeshLod lod{scene, mesh, positions.data(), std::vector<uint32_t>(mesh.vertexCount),
              // Far below a pixel at any distance the camera sees the mesh from, yet a normal float.
              std::max(1e-6f * std::max({extent.x, extent.y, extent.z}), 1e-30f),
              std::vector<uint32_t>(mesh.vertexCount, UINT32_MAX)};
  meshopt_generateVertexRemap(lod.weld.data(), nullptr, mesh.vertexCount, positions.data(), mesh.vertexCount,
                              sizeof(glm::vec3));
  for (uint32_t level = 0; level < kMaxLevels && pool.size() > 1; ++level) {
    const size_t before = scene.clusters.size();
    pool = buildLevel(lod, pool);
    if (scene.clusters.size() == before) break;  // no group simplified: the rest are roots
  }
  mesh.clusterCount = static_cast<uint32_t>(scene.clusters.size()) - mesh.firstCluster;
}

}  // namespace fgb::scene::detail
