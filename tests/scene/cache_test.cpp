// The cooked cache: round trip, corruption detection, warm loads that skip generation.
#include "test_util.hpp"

#include <fgb/core/error.hpp>
#include <fgb/scene/cache.hpp>
#include <fgb/scene/cook.hpp>
#include <fgb/scene/generators.hpp>
#include <fgb/scene/load.hpp>
#include <fgb/scene/stats.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include <fstream>

using namespace fgb::scene;
using fgb::scene::test::TempDir;
using ::testing::HasSubstr;

namespace {

// A small but complete scene: meshes, textures, lights, emitters (showcase generator).
Scene smallScene() { return generate("showcase", resolveGeneratorParams({"showcase", {}}, {}, "t")); }

// A small atrium (same structure and counts, lower density and small textures) as a scene file.
const char* kSmallAtrium = R"({"generator": {"type": "atrium", "scale": 0.02, "texture_size": 16}})";

void flipByte(const std::filesystem::path& file, std::streamoff at) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(at);
  char c = 0;
  f.read(&c, 1);
  c = static_cast<char>(c ^ 0x5a);
  f.seekp(at);
  f.write(&c, 1);
}

}  // namespace

TEST(CookedCache, RoundTripPreservesContent) {
  TempDir dir;
  CookedCache cache(dir.path());
  const Scene scene = smallScene();
  cache.store("00112233445566778899aabbccddeeff", scene, {});
  const CacheLookup lookup = cache.load("00112233445566778899aabbccddeeff", {});
  ASSERT_EQ(lookup.status, CacheStatus::Hit) << lookup.reason;
  EXPECT_EQ(contentHash(*lookup.scene), contentHash(scene));
  EXPECT_EQ(lookup.scene->textures.size(), scene.textures.size());
  EXPECT_EQ(cache.load("ffffffffffffffffffffffffffffffff", {}).status, CacheStatus::Missing);
}

TEST(CookedCache, CorruptAndTruncatedEntriesAreDetected) {
  TempDir dir;
  CookedCache cache(dir.path());
  const std::string key = "0123456789abcdef0123456789abcdef";
  cache.store(key, smallScene(), {});
  const auto entry = cache.entryPath(key);
  const auto size = std::filesystem::file_size(entry);

  flipByte(entry, static_cast<std::streamoff>(size / 2));
  CacheLookup lookup = cache.load(key, {});
  EXPECT_EQ(lookup.status, CacheStatus::Corrupt);
  EXPECT_THAT(lookup.reason, HasSubstr("checksum"));

  cache.store(key, smallScene(), {});
  std::filesystem::resize_file(entry, size - 100);
  lookup = cache.load(key, {});
  EXPECT_EQ(lookup.status, CacheStatus::Corrupt);
  EXPECT_THAT(lookup.reason, HasSubstr("truncated"));

  std::filesystem::resize_file(entry, 10);
  EXPECT_EQ(cache.load(key, {}).status, CacheStatus::Corrupt);
}

// A checksummed entry whose clusters point outside themselves (a packed corner past the cluster's
// vertex list, a vertex past its mesh) is refused like a damaged one: the shaders would index
// another cluster's vertices.
TEST(CookedCache, ClusterCornersAndVerticesOutOfRangeAreCorrupt) {
  TempDir dir;
  CookedCache cache(dir.path());
  const std::string key = "fedcba9876543210fedcba9876543210";
  Scene good = smallScene();
  cookScene(good);
  ASSERT_FALSE(good.meshes.empty());
  ASSERT_GT(good.meshes[0].clusterCount, 0u);
  const Cluster& first = good.clusters[good.meshes[0].firstCluster];
  ASSERT_LT(first.vertexCount, 255u);

  Scene corner = good;
  corner.clusterTriangles[first.firstTriangle] = packClusterTriangle(0, 1, first.vertexCount);
  cache.store(key, corner, {});
  CacheLookup lookup = cache.load(key, {});
  EXPECT_EQ(lookup.status, CacheStatus::Corrupt);
  EXPECT_THAT(lookup.reason, HasSubstr("cluster triangle corner"));

  Scene vertex = good;
  vertex.clusterVertices[first.firstVertex] = good.meshes[0].vertexCount;
  cache.store(key, vertex, {});
  lookup = cache.load(key, {});
  EXPECT_EQ(lookup.status, CacheStatus::Corrupt);
  EXPECT_THAT(lookup.reason, HasSubstr("cluster vertex"));

  cache.store(key, good, {});
  EXPECT_EQ(cache.load(key, {}).status, CacheStatus::Hit);
}

TEST(CookedCache, ChangedDependencyMakesEntryStale) {
  TempDir dir;
  CookedCache cache(dir.path() / "cache");
  dir.write("model/tex.png", "pixels-v1");
  const auto dependency = describeDependency(dir.path() / "model", "tex.png");
  ASSERT_TRUE(dependency);
  const std::string key = "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa";
  cache.store(key, smallScene(), {*dependency});
  EXPECT_EQ(cache.load(key, dir.path() / "model").status, CacheStatus::Hit);
  dir.write("model/tex.png", "pixels-v2");
  EXPECT_EQ(cache.load(key, dir.path() / "model").status, CacheStatus::Stale);
}

TEST(CacheKey, DependsOnEveryFieldAndItsBoundaries) {
  const auto key = [](std::string a, std::string b) { return CacheKey().add(a).add(b).finish(); };
  EXPECT_EQ(key("ab", "c"), key("ab", "c"));
  EXPECT_NE(key("ab", "c"), key("a", "bc"));
  EXPECT_EQ(key("x", "y").size(), 32u);
}

TEST(LoadScene, WarmLoadSkipsGenerationAndGivesTheSameScene) {
  TempDir dir;
  const auto file = dir.write("atrium-small.json", kSmallAtrium);
  LoadOptions options;
  options.cacheDir = dir.path() / "cache";
  const LoadedScene cold = loadScene(file, options);
  ASSERT_EQ(cold.parts.size(), 1u);
  EXPECT_EQ(cold.parts[0].cache, "miss");
  EXPECT_GT(cold.parts[0].produceMs, 0.0);
  EXPECT_TRUE(std::filesystem::exists(cold.parts[0].entry));

  const LoadedScene warm = loadScene(file, options);
  ASSERT_EQ(warm.parts.size(), 1u);
  EXPECT_EQ(warm.parts[0].cache, "hit");
  EXPECT_EQ(warm.parts[0].produceMs, 0.0);
  EXPECT_EQ(warm.parts[0].cookMs, 0.0);
  EXPECT_EQ(warm.hash, cold.hash);
  EXPECT_EQ(warm.scene.instances.size(), 115u);

  // Different knobs that change geometry use a different entry.
  options.knobs = {{"atrium.seed", "7"}};
  const LoadedScene other = loadScene(file, options);
  EXPECT_EQ(other.parts[0].cache, "miss");
  EXPECT_NE(other.hash, cold.hash);
}

TEST(LoadScene, CorruptEntryIsRebuiltWithANotice) {
  TempDir dir;
  const auto file = dir.write("atrium-small.json", kSmallAtrium);
  LoadOptions options;
  options.cacheDir = dir.path() / "cache";
  const LoadedScene cold = loadScene(file, options);
  flipByte(cold.parts[0].entry, 1000);
  const LoadedScene rebuilt = loadScene(file, options);
  EXPECT_EQ(rebuilt.parts[0].cache, "rebuilt");
  ASSERT_EQ(rebuilt.notices.size(), 1u);
  EXPECT_THAT(rebuilt.notices[0], HasSubstr("corrupt"));
  EXPECT_EQ(rebuilt.hash, cold.hash);
  EXPECT_EQ(loadScene(file, options).parts[0].cache, "hit");
}

TEST(LoadScene, OverridesAndKnobsApplyAfterTheCache) {
  TempDir dir;
  const auto file = dir.write("s.json", R"({
    "generator": {"type": "showcase", "lights": 2},
    "lights": [{"position": [0, 5, 0]}],
    "camera": {"fov_deg": 40},
    "post": {"exposure": 1.5}
  })");
  LoadOptions options;
  options.cacheDir = dir.path() / "cache";
  options.knobs = {{"camera.near", "0.5"}, {"post.bloom", "0"}, {"renderer.anything", "1"}};
  const LoadedScene loaded = loadScene(file, options);
  EXPECT_EQ(loaded.scene.lights.size(), 3u);
  EXPECT_FLOAT_EQ(loaded.scene.camera.verticalFovDeg, 40.0f);
  EXPECT_FLOAT_EQ(loaded.scene.camera.nearPlane, 0.5f);
  EXPECT_FLOAT_EQ(loaded.scene.post.exposure, 1.5f);
  EXPECT_FALSE(loaded.scene.post.bloom.enabled);
  options.knobs = {{"scene.lights", "0"}, {"scene.particles", "0"}};
  EXPECT_TRUE(loadScene(file, options).scene.lights.empty());

  // Stability knobs: infinite far plane, auto exposure, light and emissive scales.
  options.knobs = {
      {"camera.far", "inf"}, {"post.exposure", "auto"}, {"scene.light_scale", "1e3"}, {"scene.emissive_scale", "2"}};
  const Scene scaled = loadScene(file, options).scene;
  EXPECT_TRUE(std::isinf(scaled.camera.farPlane));
  EXPECT_TRUE(scaled.post.autoExposure);
  EXPECT_FLOAT_EQ(scaled.post.lightScale, 1e3f);
  EXPECT_FLOAT_EQ(scaled.post.bloom.threshold, loaded.scene.post.bloom.threshold * 1e3f);
  EXPECT_FLOAT_EQ(scaled.lights[0].intensity, loaded.scene.lights[0].intensity * 1e3f);
  EXPECT_FLOAT_EQ(scaled.sun.intensity, loaded.scene.sun.intensity * 1e3f);
  options.knobs = {{"post.exposure", "0"}};
  EXPECT_THROW(loadScene(file, options), fgb::InputError);

  // scene.offset moves everything, camera included, in double.
  options.knobs = {{"scene.offset", "1e7"}};
  const Scene moved = loadScene(file, options).scene;
  const auto movedBy = [](const glm::dvec3& after, const glm::dvec3& before) {
    return glm::length(after - before - glm::dvec3(1e7, 0.0, 1e7)) < 1e-8;  // double: ~2e-9 m steps
  };
  EXPECT_TRUE(movedBy(moved.camera.position, loaded.scene.camera.position));
  EXPECT_TRUE(movedBy(moved.camera.target, loaded.scene.camera.target));
  EXPECT_TRUE(movedBy(moved.lights[0].position, loaded.scene.lights[0].position));
  EXPECT_TRUE(movedBy(glm::dvec3(moved.instances[0].transform[3]), glm::dvec3(loaded.scene.instances[0].transform[3])));
  EXPECT_TRUE(movedBy(moved.instances[0].worldBounds.min, loaded.scene.instances[0].worldBounds.min));
}

TEST(LoadScene, ModelWithoutImporterOrCacheIsAClearInputError) {
  if (hasModelImporter()) GTEST_SKIP() << "an importer is linked into this test binary";
  TempDir dir;
  dir.write("box.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto file = dir.write("s.json", R"({"model": "box.obj"})");
  LoadOptions options;
  options.cacheDir = dir.path() / "cache";
  try {
    loadScene(file, options);
    FAIL();
  } catch (const fgb::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("box.obj"));
    EXPECT_THAT(e.what(), HasSubstr("no model import support"));
  }
}

TEST(LoadScene, MissingModelNamesSceneFieldAndPath) {
  TempDir dir;
  const auto file = dir.write("s.json", R"({"models": [{"file": "nope.glb"}]})");
  try {
    loadScene(file, {dir.path() / "cache", true, {}});
    FAIL();
  } catch (const fgb::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.json"));
    EXPECT_THAT(e.what(), HasSubstr("models[0]"));
    EXPECT_THAT(e.what(), HasSubstr("nope.glb"));
  }
}
