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
    LoadOptions options{cache.path(), true, {{"atrium.scale", "0.01"}, {"atrium.texture_size", "8"}}};
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
