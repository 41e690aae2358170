// Every scene file in scenes/ parses; generator-only scenes load (with low density for speed).
#include "test_util.hpp"

#include <fgb/scene/load.hpp>
#include <fgb/scene/scene_file.hpp>
#include <fgb/scene/stats.hpp>

#include <gtest/gtest.h>

using namespace fgb::scene;

namespace {

std::vector<std::filesystem::path> sceneFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(FGBENCH_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST(ScenesDirectory, EveryFileParses) {
  const auto files = sceneFiles();
  EXPECT_GE(files.size(), 10u);
  for (const auto& file : files) EXPECT_NO_THROW(parseSceneFile(file)) << file;
}

TEST(ScenesDirectory, GeneratorOnlyScenesLoad) {
  fgb::scene::test::TempDir cache;
  for (const auto& file : sceneFiles()) {
    const SceneDescription d = parseSceneFile(file);
    if (!d.models.empty()) continue;  // model scenes are tested with the importer (tests/import)
    LoadOptions options{
        cache.path(),
        true,
        {{"atrium.scale", "0.01"}, {"atrium.texture_size", "8"}, {"city.blocks", "2"}, {"city.texture_size", "8"}}};
    const LoadedScene loaded = loadScene(file, options);
    const SceneStats s = stats(loaded.scene);
    SCOPED_TRACE(file.string());
    if (d.name == "empty") {
      EXPECT_EQ(s.instances, 0u);
    }
    if (d.name == "no-lights") {
      EXPECT_EQ(s.lights, 0u);
    }
    if (d.name == "no-particles") {
      EXPECT_EQ(s.emitters, 0u);
    }
    if (d.name == "particles-only") {
      EXPECT_EQ(s.instances, 0u);
      EXPECT_GE(s.emitters, 1u);
    }
    if (d.name == "transparency-only") {
      for (const auto& instance : loaded.scene.instances) {
        EXPECT_NE(loaded.scene.materials[instance.material].alphaMode, AlphaMode::Opaque);
      }
    }
  }
}

// The city walk keeps to the streets: at every blocks (the path stays within 60 m of the origin,
// whose streets every city has) no point of the path lies inside or within the near plane's reach
// of an instance's bounds, the road and the pavements (under the eye) aside.
TEST(ScenesDirectory, CityWalkKeepsToTheStreets) {
  fgb::scene::test::TempDir cache;
  const auto file = std::filesystem::path(FGBENCH_SOURCE_DIR) / "scenes" / "city-walk.json";
  for (const char* blocks : {"2", "9"}) {
    SCOPED_TRACE(std::string("city.blocks=") + blocks);
    LoadOptions options{cache.path(), true, {{"city.blocks", blocks}, {"city.texture_size", "8"}}};
    const Scene scene = loadScene(file, options).scene;
    ASSERT_GT(scene.cameraPath.duration(), 30.0);
    for (double t = 0.0; t <= scene.cameraPath.duration(); t += 0.25) {
      const glm::dvec3 eye = scene.cameraPath.at(scene.camera, t).position;
      for (const Instance& instance : scene.instances) {
        const std::string& mesh = scene.meshes[instance.mesh].name;
        if (mesh == "road" || mesh == "pavement") continue;
        const glm::dvec3 lo = instance.worldBounds.min - 0.5, hi = instance.worldBounds.max + 0.5;
        const bool inside = glm::all(glm::greaterThan(eye, lo)) && glm::all(glm::lessThan(eye, hi));
        ASSERT_FALSE(inside) << "at t = " << t << " s the eye " << eye.x << "," << eye.y << "," << eye.z
                             << " is inside " << mesh;
      }
    }
  }
}
