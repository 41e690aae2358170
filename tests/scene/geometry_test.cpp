// Mesh repair, tangents, bounds and merging.
#include <fgb/core/error.hpp>
#include <fgb/scene/cook.hpp>
#include <fgb/scene/geometry.hpp>
#include <fgb/scene/texture.hpp>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace fgb::scene;
using ::testing::HasSubstr;

namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();

// Two triangles forming a unit quad in the XY plane, facing +z.
MeshData quad() {
  MeshData mesh;
  mesh.name = "quad";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  mesh.uv0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

bool allFinite(const MeshData& m) {
  for (const auto& p : m.positions) if (!std::isfinite(p.x + p.y + p.z)) return false;
  for (const auto& n : m.normals) if (!std::isfinite(n.x + n.y + n.z)) return false;
  for (const auto& t : m.tangents) if (!std::isfinite(t.x + t.y + t.z + t.w)) return false;
  for (const auto& uv : m.uv0) if (!std::isfinite(uv.x + uv.y)) return false;
  return true;
}

}  // namespace

TEST(RepairMesh, CleanMeshNeedsOnlyTangents) {
  MeshData mesh = quad();
  RepairCounters repairs;
  repairMesh(mesh, repairs, "test");
  EXPECT_EQ(repairs.generatedTangents, 1u);
  EXPECT_EQ(repairs.total(), 1u);
  ASSERT_EQ(mesh.tangents.size(), 4u);
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(t.x, 1.0f, 1e-5f);  // u runs along +x
    EXPECT_NEAR(t.w, 1.0f, 1e-5f);
  }
}

TEST(RepairMesh, NanAndZeroNormalsAreRecomputedAndCounted) {
  MeshData mesh = quad();
  mesh.normals[1] = glm::vec3(kNan);
  mesh.normals[2] = glm::vec3(0.0f);
  RepairCounters repairs;
  repairMesh(mesh, repairs, "test");
  EXPECT_EQ(repairs.nonFiniteNormals, 1u);
  EXPECT_EQ(repairs.zeroNormals, 1u);
  for (const glm::vec3& n : mesh.normals) EXPECT_NEAR(n.z, 1.0f, 1e-5f);
}

TEST(RepairMesh, DegenerateZeroAreaAndNonFiniteTrianglesAreRemoved) {
  MeshData mesh = quad();
  mesh.positions.push_back({2, 0, 0});        // 4: collinear with 0 and 1
  mesh.positions.push_back({kNan, 0, 0});     // 5: NaN
  mesh.normals.resize(6, glm::vec3(0, 0, 1));
  mesh.uv0.resize(6, glm::vec2(0.0f));
  mesh.indices.insert(mesh.indices.end(), {0, 1, 1,   0, 1, 4,   0, 5, 2});
  RepairCounters repairs;
  repairMesh(mesh, repairs, "test");
  EXPECT_EQ(repairs.degenerateTriangles, 1u);
  EXPECT_EQ(repairs.zeroAreaTriangles, 1u);
  EXPECT_EQ(repairs.nonFiniteTriangles, 1u);
  EXPECT_EQ(repairs.nonFinitePositions, 1u);
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_EQ(mesh.positions.size(), 4u);  // unreferenced vertices (the NaN one) are dropped
  EXPECT_TRUE(allFinite(mesh));
}

TEST(RepairMesh, SliversSurvive) {
  MeshData mesh;
  mesh.name = "sliver";
  mesh.positions = {{0, 0, 0}, {10, 0, 0}, {5, 1e-3f, 0}};
  mesh.indices = {0, 1, 2};
  RepairCounters repairs;
  repairMesh(mesh, repairs, "test");
  EXPECT_EQ(mesh.triangleCount(), 1u);
  EXPECT_EQ(repairs.zeroAreaTriangles, 0u);
  EXPECT_EQ(repairs.generatedNormals, 1u);
}

TEST(RepairMesh, IndexOutOfRangeNamesContextAndMesh) {
  MeshData mesh = quad();
  mesh.indices[4] = 17;
  RepairCounters repairs;
  try {
    repairMesh(mesh, repairs, "models/box.gltf");
    FAIL() << "expected InputError";
  } catch (const fgb::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("models/box.gltf"));
    EXPECT_THAT(e.what(), HasSubstr("mesh 'quad'"));
    EXPECT_THAT(e.what(), HasSubstr("index 17"));
  }
}

TEST(RepairMesh, BadTangentsAndUvsAreRepaired) {
  MeshData mesh = quad();
  mesh.tangents = {{1, 0, 0, 1}, {kNan, 0, 0, 1}, {0, 0, 1, 1}, {0, 0, 0, 1}};  // NaN, parallel, zero
  mesh.uv0[3] = glm::vec2(kNan, 0.0f);
  RepairCounters repairs;
  repairMesh(mesh, repairs, "test");
  EXPECT_EQ(repairs.nonFiniteTangents, 1u);
  EXPECT_EQ(repairs.zeroTangents, 2u);
  EXPECT_EQ(repairs.nonFiniteUvs, 1u);
  EXPECT_TRUE(allFinite(mesh));
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(glm::length(glm::vec3(mesh.tangents[v])), 1.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(glm::vec3(mesh.tangents[v]), mesh.normals[v]), 0.0f, 1e-4f);
  }
}

TEST(Aabb, TransformedContainsAllCorners) {
  const Aabb box{{-1, -2, -3}, {1, 2, 3}};
  const glm::mat4 m = glm::rotate(glm::translate(glm::mat4(1.0f), {5, 0, 0}), 0.7f, glm::vec3(0, 1, 0));
  const Aabb t = box.transformed(m);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                      (corner & 4) ? box.max.z : box.min.z);
    const glm::vec3 q(m * glm::vec4(p, 1.0f));
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(t.min[a], q[a] + 1e-5f);
      EXPECT_GE(t.max[a], q[a] - 1e-5f);
    }
  }
  EXPECT_NEAR(t.min.y, -2.0f, 1e-5f);
}

TEST(MergeScene, RenumbersAndPlaces) {
  Scene a, b;
  MeshData qa = quad(), qb = quad();
  RepairCounters r;
  repairMesh(qa, r, "a");
  repairMesh(qb, r, "b");
  addInstance(a, appendMesh(a, std::move(qa)), 0, glm::mat4(1.0f));
  a.materials.resize(1);
  b.materials.resize(1);
  b.materials[0].baseColorTexture = 0;
  b.textures.push_back(fallbackTexture("x.png", true));
  addInstance(b, appendMesh(b, std::move(qb)), 0, glm::mat4(1.0f));
  b.lights.push_back({{0, 0, 0}, glm::vec3(1.0f), 1.0f, 2.0f});
  mergeScene(a, std::move(b), glm::scale(glm::translate(glm::mat4(1.0f), {10, 0, 0}), glm::vec3(2.0f)));
  ASSERT_EQ(a.instances.size(), 2u);
  EXPECT_EQ(a.instances[1].mesh, 1u);
  EXPECT_EQ(a.instances[1].material, 1u);
  EXPECT_EQ(a.meshes[1].firstVertex, 4u);
  EXPECT_EQ(a.meshes[1].firstIndex, 6u);
  EXPECT_EQ(a.materials[1].baseColorTexture, 0);
  EXPECT_FLOAT_EQ(a.instances[1].worldBounds.min.x, 10.0f);
  EXPECT_FLOAT_EQ(a.instances[1].worldBounds.max.x, 12.0f);
  EXPECT_FLOAT_EQ(a.lights[0].position.x, 10.0f);
  EXPECT_NEAR(a.lights[0].radius, 4.0f, 1e-4f);
}

// Cooked parts bring their clusters: the merged meshes point at their own clusters, whose
// triangle and vertex ranges point at their own packed triangles and (mesh-local) vertex lists.
TEST(MergeScene, KeepsEachPartsClusters) {
  Scene a, b;
  MeshData qa = quad(), qb = quad();
  RepairCounters r;
  repairMesh(qa, r, "a");
  repairMesh(qb, r, "b");
  addInstance(a, appendMesh(a, std::move(qa)), 0, glm::mat4(1.0f));
  addInstance(b, appendMesh(b, std::move(qb)), 0, glm::mat4(1.0f));
  a.materials.resize(1);
  b.materials.resize(1);
  cookScene(a);
  cookScene(b);
  ASSERT_EQ(a.clusters.size(), 1u);
  ASSERT_EQ(b.clusters.size(), 1u);
  const std::vector<uint32_t> partTriangles = b.clusterTriangles;
  const std::vector<uint32_t> partVertices = b.clusterVertices;
  ASSERT_EQ(partVertices.size(), 4u);
  mergeScene(a, std::move(b), glm::mat4(1.0f));
  ASSERT_EQ(a.clusters.size(), 2u);
  EXPECT_EQ(a.meshes[1].firstCluster, 1u);
  EXPECT_EQ(a.meshes[1].clusterCount, 1u);
  const Cluster& merged = a.clusters[1];
  EXPECT_EQ(merged.firstTriangle, 2u);
  EXPECT_EQ(merged.firstVertex, 4u);
  ASSERT_EQ(merged.triangleCount, 2u);
  ASSERT_EQ(merged.vertexCount, 4u);
  for (uint32_t t = 0; t < 2; ++t) EXPECT_EQ(a.clusterTriangles[merged.firstTriangle + t], partTriangles[t]);
  for (uint32_t v = 0; v < 4; ++v) EXPECT_EQ(a.clusterVertices[merged.firstVertex + v], partVertices[v]);
}

TEST(Texture, MipChainReachesOnePixelAndAveragesInLinearSpace) {
  // 4x2, left half black, right half white (sRGB): the 1x1 level is linear 0.5 -> sRGB ~188.
  std::vector<uint8_t> texels(4 * 2 * 4, 255);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      for (int c = 0; c < 3; ++c) texels[(y * 4 + x) * 4 + c] = 0;
  const Texture t = makeTexture("t", 4, 2, texels, true);
  ASSERT_EQ(t.mips.size(), 3u);
  EXPECT_EQ(t.mips[2].width, 1u);
  EXPECT_EQ(t.mips[2].height, 1u);
  EXPECT_NEAR(t.data[t.mips[2].offset], 188, 1);
  EXPECT_EQ(t.data[t.mips[2].offset + 3], 255);
  EXPECT_THROW(makeTexture("bad", 4, 4, texels, false), fgb::InputError);
}
