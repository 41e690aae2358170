// Material and texture conversion.
#include "materials.hpp"

#include "image_decode.hpp"

#include <fgb/scene/texture.hpp>

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace fgb::import {
namespace {

glm::vec4 colour(const aiMaterial& m, const char* key, unsigned type, unsigned index, glm::vec4 fallback) {
  aiColor4D c;
  if (m.Get(key, type, index, c) == AI_SUCCESS) return {c.r, c.g, c.b, c.a};
  return fallback;
}

float number(const aiMaterial& m, const char* key, unsigned type, unsigned index, float fallback) {
  float value = 0.0f;
  if (m.Get(key, type, index, value) == AI_SUCCESS && std::isfinite(value)) return value;
  return fallback;
}

bool finiteColour(const glm::vec4& c) { return std::isfinite(c.r + c.g + c.b + c.a); }

// Texel data of an uncompressed embedded texture (aiTexel is BGRA).
std::vector<uint8_t> fromTexels(const aiTexture& t) {
  std::vector<uint8_t> rgba(size_t(t.mWidth) * t.mHeight * 4);
  for (size_t i = 0; i < size_t(t.mWidth) * t.mHeight; ++i) {
    rgba[i * 4 + 0] = t.pcData[i].r;
    rgba[i * 4 + 1] = t.pcData[i].g;
    rgba[i * 4 + 2] = t.pcData[i].b;
    rgba[i * 4 + 3] = t.pcData[i].a;
  }
  return rgba;
}

}  // namespace

MaterialConverter::MaterialConverter(const aiScene& source, std::filesystem::path modelFile, scene::Scene& target,
                                     std::set<std::string>& dependencies)
    : source_(source), modelFile_(std::move(modelFile)), target_(target), dependencies_(dependencies) {}

void MaterialConverter::convertAll() {
  for (unsigned i = 0; i < source_.mNumMaterials; ++i) target_.materials.push_back(convert(*source_.mMaterials[i], i));
}

scene::Material MaterialConverter::convert(const aiMaterial& m, unsigned index) {
  scene::Material out;
  aiString name;
  out.name = m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length ? name.C_Str() : "material-" + std::to_string(index);

  // glTF materials carry a base colour; older formats a diffuse colour and Phong shininess.
  glm::vec4 base = colour(m, AI_MATKEY_BASE_COLOR, glm::vec4(-1.0f));
  const bool pbr = base.r >= 0.0f;
  if (!pbr) base = colour(m, AI_MATKEY_COLOR_DIFFUSE, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));
  const float opacity = number(m, AI_MATKEY_OPACITY, 1.0f);
  base.a *= std::clamp(opacity, 0.0f, 1.0f);
  out.baseColorFactor = finiteColour(base) ? glm::clamp(base, 0.0f, 1.0f) : glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  out.metallicFactor = std::clamp(number(m, AI_MATKEY_METALLIC_FACTOR, pbr ? 1.0f : 0.0f), 0.0f, 1.0f);
  const float shininess = number(m, AI_MATKEY_SHININESS, 0.0f);
  const float phongRoughness = shininess > 0.0f ? std::sqrt(2.0f / (shininess + 2.0f)) : 0.8f;
  out.roughnessFactor = std::clamp(number(m, AI_MATKEY_ROUGHNESS_FACTOR, pbr ? 1.0f : phongRoughness), 0.0f, 1.0f);
  const glm::vec4 emissive = colour(m, AI_MATKEY_COLOR_EMISSIVE, glm::vec4(0.0f));
  out.emissiveFactor = finiteColour(emissive) ? glm::max(glm::vec3(emissive), glm::vec3(0.0f)) : glm::vec3(0.0f);
  out.emissiveStrength = std::max(0.0f, number(m, AI_MATKEY_EMISSIVE_INTENSITY, 1.0f));

  aiString alphaMode;
  if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, alphaMode) == AI_SUCCESS) {
    if (std::strcmp(alphaMode.C_Str(), "MASK") == 0) out.alphaMode = scene::AlphaMode::Mask;
    if (std::strcmp(alphaMode.C_Str(), "BLEND") == 0) out.alphaMode = scene::AlphaMode::Blend;
  } else if (out.baseColorFactor.a < 1.0f) {
    out.alphaMode = scene::AlphaMode::Blend;
  }
  out.alphaCutoff = std::clamp(number(m, AI_MATKEY_GLTF_ALPHACUTOFF, 0.5f), 0.0f, 1.0f);
  int twoSided = 0;
  out.doubleSided = m.Get(AI_MATKEY_TWOSIDED, twoSided) == AI_SUCCESS && twoSided != 0;

  out.baseColorTexture = texture(m, aiTextureType_BASE_COLOR, true, true);
  if (out.baseColorTexture < 0) out.baseColorTexture = texture(m, aiTextureType_DIFFUSE, true, true);
  // A missing normal or metallic-roughness map falls back to "none" (a checkerboard would shade
  // nonsense); it is still warned about and counted.
  out.normalTexture = texture(m, aiTextureType_NORMALS, false, false);
  // glTF metallicRoughness maps arrive as aiTextureType_UNKNOWN (AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_...).
  out.metallicRoughnessTexture = texture(m, aiTextureType_UNKNOWN, false, false);
  out.emissiveTexture = texture(m, aiTextureType_EMISSIVE, true, true);
  return out;
}

int32_t MaterialConverter::texture(const aiMaterial& m, int type, bool srgb, bool fallbackWhenMissing) {
  const auto textureType = static_cast<aiTextureType>(type);
  if (m.GetTextureCount(textureType) == 0) return -1;
  aiString path;
  if (m.GetTexture(textureType, 0, &path) != AI_SUCCESS || path.length == 0) return -1;
  return decode(path.C_Str(), srgb, fallbackWhenMissing);
}

int32_t MaterialConverter::decode(const std::string& reference, bool srgb, bool fallbackWhenMissing) {
  const auto key = std::make_pair(reference, srgb);
  if (const auto it = decoded_.find(key); it != decoded_.end()) return it->second;

  std::string error;
  std::optional<DecodedImage> image;
  std::string name = reference;
  if (const aiTexture* embedded = source_.GetEmbeddedTexture(reference.c_str())) {
    name = "embedded:" + reference;
    if (embedded->mHeight == 0) {
      const auto* bytes = reinterpret_cast<const uint8_t*>(embedded->pcData);
      image = decodeImageMemory({bytes, embedded->mWidth}, embedded->achFormatHint, error);
    } else {
      image = DecodedImage{embedded->mWidth, embedded->mHeight, fromTexels(*embedded)};
    }
  } else {
    std::string relative = reference;
    std::replace(relative.begin(), relative.end(), '\\', '/');
    const std::filesystem::path file = modelFile_.parent_path() / relative;
    image = decodeImageFile(file, error);
    dependencies_.insert(relative);  // recorded even when missing: adding it later must re-cook
    name = file.string();
  }

  int32_t index = -1;
  if (image) {
    index = add(scene::makeTexture(name, image->width, image->height, std::move(image->rgba), srgb));
  } else {
    ++target_.repairs.missingTextures;
    target_.warnings.push_back(modelFile_.string() + ": texture '" + reference + "' could not be loaded (" + error +
                               ")" + (fallbackWhenMissing ? "; using the fallback checkerboard" : "; ignored"));
    if (fallbackWhenMissing) index = add(scene::fallbackTexture(reference, srgb));
  }
  decoded_[key] = index;
  return index;
}

int32_t MaterialConverter::add(scene::Texture&& texture) {
  target_.textures.push_back(std::move(texture));
  return static_cast<int32_t>(target_.textures.size() - 1);
}

}  // namespace fgb::import
