// Model import against real third-party files (Debian's assimp-testmodels), and against copies
// of them corrupted here: NaN normals, out-of-range indices, truncation, missing textures.
#include <fgb/core/error.hpp>
#include <fgb/import/model_importer.hpp>
#include <fgb/import/module_loader.hpp>
#include <fgb/scene/cook.hpp>
#include <fgb/scene/load.hpp>
#include <fgb/scene/stats.hpp>

#include "test_util.hpp"  // tests/scene: TempDir

#include <glm/geometric.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>


using namespace fgb::scene;
using fgb::import::importModel;
using ::testing::HasSubstr;
using fgb::scene::test::TempDir;

namespace {

const std::filesystem::path kModels = ASSIMP_MODELS;

// Copies the textured box glTF (.gltf + .bin + .png) into `dir`; returns the .gltf path.
std::filesystem::path copyBoxGltf(const std::filesystem::path& dir) {
  for (const char* name : {"BoxTextured.gltf", "BoxTextured0.bin", "CesiumLogoFlat.png"}) {
    std::filesystem::copy_file(kModels / "glTF2/BoxTextured-glTF" / name, dir / name);
  }
  return dir / "BoxTextured.gltf";
}

// Byte range of a glTF accessor's data inside the (single) .bin buffer.
struct AccessorBytes {
  size_t offset;
  size_t count;
  size_t stride;
};

AccessorBytes accessorBytes(const std::filesystem::path& gltf, const std::string& attribute) {
  const auto doc = nlohmann::json::parse(std::ifstream(gltf));
  const auto& primitive = doc["meshes"][0]["primitives"][0];
  const int accessorIndex = attribute == "indices" ? primitive["indices"].get<int>()
                                                   : primitive["attributes"][attribute].get<int>();
  const auto& accessor = doc["accessors"][accessorIndex];
  const auto& view = doc["bufferViews"][accessor["bufferView"].get<int>()];
  const size_t elementSize = attribute == "indices" ? (accessor["componentType"] == 5123 ? 2 : 4) : 12;
  return {view.value("byteOffset", size_t{0}) + accessor.value("byteOffset", size_t{0}), accessor["count"].get<size_t>(),
          view.value("byteStride", elementSize)};
}

void patch(const std::filesystem::path& file, size_t offset, const void* bytes, size_t size) {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(offset));
  f.write(static_cast<const char*>(bytes), static_cast<std::streamsize>(size));
}

std::string importError(const std::filesystem::path& model) {
  try {
    importModel(model);
  } catch (const fgb::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

bool renderReady(Scene& scene) {
  cookScene(scene);
  for (const auto& p : scene.positions) if (!std::isfinite(p.x + p.y + p.z)) return false;
  for (const auto& n : scene.normals) if (std::abs(glm::length(n) - 1.0f) > 1e-3f) return false;
  for (const auto& t : scene.tangents) if (!std::isfinite(t.x + t.y + t.z + t.w)) return false;
  return !scene.instances.empty() && !scene.materials.empty();
}

}  // namespace

TEST(Import, SeveralFormatsFromAssimpTestModels) {
  struct Case {
    const char* file;
    size_t textures;
  };
  const Case cases[] = {{"glTF2/BoxTextured-glTF/BoxTextured.gltf", 1}, {"glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", 1},
                        {"OBJ/spider.obj", 5},   {"FBX/box.fbx", 0}, {"Collada/duck.dae", 1}, {"3DS/fels.3ds", 0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    ImportedModel model = importModel(kModels / c.file);
    EXPECT_GT(stats(model.scene).triangles, 0u);
    EXPECT_EQ(model.scene.textures.size(), c.textures);
    EXPECT_TRUE(model.scene.warnings.empty());
    EXPECT_TRUE(renderReady(model.scene));
  }
}

TEST(Import, EmbeddedAndExternalTexturesAreDecodedWithMips) {
  const ImportedModel glb = importModel(kModels / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
  ASSERT_EQ(glb.scene.textures.size(), 1u);
  EXPECT_THAT(glb.scene.textures[0].name, HasSubstr("embedded:"));
  EXPECT_TRUE(glb.scene.textures[0].srgb);
  EXPECT_EQ(glb.scene.textures[0].mips.back().width, 1u);
  const ImportedModel gltf = importModel(kModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf");
  EXPECT_EQ(gltf.scene.textures[0].width, glb.scene.textures[0].width);
  EXPECT_EQ(gltf.scene.textures[0].data, glb.scene.textures[0].data);  // same PNG, embedded or not
  EXPECT_THAT(gltf.dependencies, ::testing::UnorderedElementsAre("BoxTextured0.bin", "CesiumLogoFlat.png"));
}

TEST(Import, ShippedBadNormalsAreRepairedAndCounted) {
  ImportedModel model = importModel(kModels / "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  EXPECT_GT(model.scene.repairs.zeroNormals + model.scene.repairs.nonFiniteNormals, 0u);
  EXPECT_TRUE(renderReady(model.scene));
}

TEST(Import, ShippedInfinitePositionsAreRemovedAndCounted) {
  ImportedModel model = importModel(kModels / "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb");
  EXPECT_GT(model.scene.repairs.nonFinitePositions, 0u);
  EXPECT_GT(model.scene.repairs.nonFiniteTriangles, 0u);
}

TEST(Import, CorruptedNormalsInACopiedGltfAreRepairedAndCounted) {
  TempDir dir;
  const auto gltf = copyBoxGltf(dir.path());
  const AccessorBytes normals = accessorBytes(gltf, "NORMAL");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float zero[3] = {0, 0, 0}, bad[3] = {nan, 0, 1};
  patch(dir.path() / "BoxTextured0.bin", normals.offset, bad, sizeof bad);
  patch(dir.path() / "BoxTextured0.bin", normals.offset + normals.stride, zero, sizeof zero);
  ImportedModel model = importModel(gltf);
  EXPECT_EQ(model.scene.repairs.nonFiniteNormals, 1u);
  EXPECT_EQ(model.scene.repairs.zeroNormals, 1u);
  EXPECT_TRUE(renderReady(model.scene));
}

TEST(Import, OutOfRangeIndexNamesFileAndMesh) {
  TempDir dir;
  const auto gltf = copyBoxGltf(dir.path());
  const AccessorBytes indices = accessorBytes(gltf, "indices");
  const uint16_t outOfRange = 60000;
  patch(dir.path() / "BoxTextured0.bin", indices.offset + 2, &outOfRange, sizeof outOfRange);
  const std::string error = importError(gltf);
  EXPECT_THAT(error, HasSubstr(gltf.string()));
  EXPECT_THAT(error, HasSubstr("mesh"));
  EXPECT_THAT(error, HasSubstr("out of range"));
  EXPECT_EQ(error.find('\n'), std::string::npos);
  EXPECT_THAT(importError(kModels / "glTF2/IndexOutOfRange/IndexOutOfRange.gltf"), HasSubstr("mesh 'Mesh'"));
}

TEST(Import, TruncatedUnsupportedAndMissingFilesAreInputErrors) {
  TempDir dir;
  const auto glb = dir.path() / "truncated.glb";
  std::filesystem::copy_file(kModels / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", glb);
  std::filesystem::resize_file(glb, std::filesystem::file_size(glb) / 2);
  EXPECT_THAT(importError(glb), HasSubstr("truncated.glb"));

  const auto garbage = dir.path() / "model.xyz";
  std::ofstream(garbage) << "this is not a model\n";
  EXPECT_THAT(importError(garbage), HasSubstr("model.xyz"));

  EXPECT_THAT(importError(kModels / "glTF2/MissingBin/BoxTextured.gltf"), HasSubstr("BoxTextured0.bin"));
  EXPECT_THAT(importError(kModels / "invalid/malformed.obj"), HasSubstr("malformed.obj"));
  EXPECT_THAT(importError(kModels / "glTF2/RecursiveNodes/RecursiveNodes.gltf"), HasSubstr("RecursiveNodes.gltf"));
}

TEST(Import, MissingTextureGivesFallbackAndOneWarningNamingIt) {
  TempDir dir;
  const auto gltf = copyBoxGltf(dir.path());
  std::filesystem::remove(dir.path() / "CesiumLogoFlat.png");
  ImportedModel model = importModel(gltf);
  EXPECT_EQ(model.scene.repairs.missingTextures, 1u);
  ASSERT_EQ(model.scene.warnings.size(), 1u);
  EXPECT_THAT(model.scene.warnings[0], HasSubstr("CesiumLogoFlat.png"));
  ASSERT_EQ(model.scene.textures.size(), 1u);
  EXPECT_EQ(model.scene.textures[0].name, "fallback:CesiumLogoFlat.png");
  EXPECT_TRUE(renderReady(model.scene));

  // The FBX spider's textures point at a Windows path that does not exist here.
  const ImportedModel spider = importModel(kModels / "FBX/spider.fbx");
  EXPECT_EQ(spider.scene.repairs.missingTextures, spider.scene.warnings.size());
  EXPECT_GT(spider.scene.warnings.size(), 0u);
}

TEST(ImportCache, WarmLoadSkipsImportAndTextureChangeRebuilds) {
  fgb::import::enableModelImport();
  TempDir dir;
  copyBoxGltf(dir.path());
  std::ofstream(dir.path() / "box.json") << R"({"model": "BoxTextured.gltf", "lights": [{"position": [0, 3, 0]}]})";
  LoadOptions options;
  options.cacheDir = dir.path() / "cache";
  const LoadedScene cold = loadScene(dir.path() / "box.json", options);
  ASSERT_EQ(cold.parts.size(), 1u);
  EXPECT_EQ(cold.parts[0].cache, "miss");
  const LoadedScene warm = loadScene(dir.path() / "box.json", options);
  EXPECT_EQ(warm.parts[0].cache, "hit");
  EXPECT_EQ(warm.parts[0].produceMs, 0.0);
  EXPECT_EQ(warm.hash, cold.hash);

  std::filesystem::remove(dir.path() / "CesiumLogoFlat.png");
  std::filesystem::copy_file(kModels / "glTF2/BoxTexcoords-glTF/texture.png", dir.path() / "CesiumLogoFlat.png");
  const LoadedScene changed = loadScene(dir.path() / "box.json", options);
  EXPECT_EQ(changed.parts[0].cache, "rebuilt");
  EXPECT_NE(changed.hash, cold.hash);
}

TEST(ImportScenes, EveryModelSceneInScenesLoads) {
  fgb::import::enableModelImport();
  TempDir cache;
  size_t modelScenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(FGBENCH_SOURCE_DIR) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    const SceneDescription d = parseSceneFile(entry.path());
    if (d.models.empty()) continue;
    SCOPED_TRACE(entry.path().string());
    ++modelScenes;
    LoadedScene loaded = loadScene(entry.path(), {cache.path(), true, {}});
    EXPECT_GT(stats(loaded.scene).triangles, 0u);
    EXPECT_TRUE(loaded.scene.hasCamera);
    EXPECT_GT(stats(loaded.scene).instancesVisible, 0u);  // the fitted camera sees the model
  }
  EXPECT_GE(modelScenes, 5u);
}

// fgbench imports through libfgb_import.so, loaded on the first cache miss: a module that cannot
// be loaded is an input error naming it, and the loaded module cooks exactly what the linked
// importer cooks (same cache key, same scene).
TEST(ImportModule, MissingModuleIsAnInputErrorAndTheRealOneMatchesTheLinkedImporter) {
  TempDir dir;
  copyBoxGltf(dir.path());
  std::ofstream(dir.path() / "box.json") << R"({"model": "BoxTextured.gltf", "lights": [{"position": [0, 3, 0]}]})";
  LoadOptions options;
  options.cacheDir = dir.path() / "cache-module";

  const std::string missing = (dir.path() / "no-such-module.so").string();
  ::setenv("FGBENCH_IMPORT_MODULE", missing.c_str(), 1);
  fgb::import::enableModelImportOnDemand();
  try {
    loadScene(dir.path() / "box.json", options);
    ADD_FAILURE() << "loading with a missing import module did not fail";
  } catch (const fgb::InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr(missing));
  }

  ::setenv("FGBENCH_IMPORT_MODULE", FGB_IMPORT_MODULE_PATH, 1);
  const LoadedScene viaModule = loadScene(dir.path() / "box.json", options);
  ::unsetenv("FGBENCH_IMPORT_MODULE");
  EXPECT_EQ(viaModule.parts.at(0).cache, "miss");

  fgb::import::enableModelImport();
  options.cacheDir = dir.path() / "cache-linked";
  const LoadedScene linked = loadScene(dir.path() / "box.json", options);
  EXPECT_EQ(viaModule.hash, linked.hash);
  EXPECT_EQ(stats(viaModule.scene).triangles, stats(linked.scene).triangles);
}
