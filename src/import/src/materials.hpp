// Private: Assimp materials -> glTF metallic-roughness materials, with textures decoded once each.
#pragma once

#include <fgb/scene/scene.hpp>

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>

struct aiScene;
struct aiMaterial;

namespace fgb::import {

class MaterialConverter {
 public:
  MaterialConverter(const aiScene& source, std::filesystem::path modelFile, scene::Scene& target,
                    std::set<std::string>& dependencies);

  // Converts every material of the source scene (same numbering).
  void convertAll();

 private:
  scene::Material convert(const aiMaterial& material, unsigned index);
  int32_t texture(const aiMaterial& material, int type, bool srgb, bool fallbackWhenMissing);
  int32_t decode(const std::string& reference, bool srgb, bool fallbackWhenMissing);
  int32_t add(scene::Texture&& texture);

  const aiScene& source_;
  std::filesystem::path modelFile_;
  scene::Scene& target_;
  std::set<std::string>& dependencies_;
  std::map<std::pair<std::string, bool>, int32_t> decoded_;  // (reference, srgb) -> texture index
};

}  // namespace fgb::import
