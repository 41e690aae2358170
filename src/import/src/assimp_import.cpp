// Assimp scene -> uncooked fgb scene: meshes (repaired), node instances, lights, camera.
#include <fgb/import/model_importer.hpp>

#include "materials.hpp"

#include <fgb/core/error.hpp>
#include <fgb/scene/geometry.hpp>

#include <assimp/DefaultIOSystem.h>
#include <assimp/DefaultLogger.hpp>
#include <assimp/Logger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <memory>
#include <mutex>
#include <set>
#include <utility>

namespace fgb::import {
namespace {

// Triangulate (quads/polygons), weld identical vertices, split point/line primitives into their
// own meshes, and flip V so UV (0,0) is the first texel of the first stored row (Vulkan's origin).
// Deliberately NOT used: FindInvalidData/FindDegenerates/ValidateDataStructure and normal or
// tangent generation -- fgb::scene::repairMesh does that, and counts what it fixed.
constexpr unsigned kPostProcess =
    aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType | aiProcess_FlipUVs;
static_assert(kPostProcess == kImportPostProcessFlags, "the cache key's flags (import_module.hpp) must match the import's");
constexpr unsigned kMaxNodeDepth = 256;

// Records every file Assimp opens (the model, .bin buffers, .mtl libraries) for the cache.
class RecordingIoSystem : public Assimp::DefaultIOSystem {
 public:
  explicit RecordingIoSystem(std::filesystem::path base) : base_(std::move(base)) {}
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    Assimp::IOStream* stream = DefaultIOSystem::Open(file, mode);
    if (stream) opened_.insert(relativeToBase(file));
    return stream;
  }
  const std::set<std::string>& opened() const { return opened_; }

 private:
  std::string relativeToBase(const std::filesystem::path& file) const {
    std::error_code error;
    const auto relative = std::filesystem::relative(file, base_, error);
    if (error || relative.empty() || *relative.begin() == "..") return std::filesystem::absolute(file).string();
    return relative.generic_string();
  }
  std::filesystem::path base_;
  std::set<std::string> opened_;
};

// Collects Assimp's warnings during one import. Some importers repair silently and only log it
// (glTF2 drops faces with out-of-range indices); the contract makes those an input error.
class WarningCollector : public Assimp::Logger {
 public:
  explicit WarningCollector(std::vector<std::string>& sink) : Logger(Logger::NORMAL), sink_(sink) {}
  bool attachStream(Assimp::LogStream* stream, unsigned int) override {
    delete stream;  // the logger owns attached streams; this one has no use for them
    return true;
  }
  bool detachStream(Assimp::LogStream*, unsigned int) override { return true; }
  void OnVerboseDebug(const char*) override {}
  void OnDebug(const char*) override {}
  void OnInfo(const char*) override {}
  void OnWarn(const char* message) override { sink_.emplace_back(message); }
  void OnError(const char* message) override { sink_.emplace_back(message); }

 private:
  std::vector<std::string>& sink_;
};

// Installs a WarningCollector as Assimp's (process-global) logger for its lifetime; imports are
// serialised because the logger is global.
class ScopedWarningCapture {
 public:
  ScopedWarningCapture() : lock_(mutex()) { Assimp::DefaultLogger::set(new WarningCollector(warnings_)); }
  ~ScopedWarningCapture() { Assimp::DefaultLogger::set(nullptr); }  // deletes the collector
  ScopedWarningCapture(const ScopedWarningCapture&) = delete;
  ScopedWarningCapture& operator=(const ScopedWarningCapture&) = delete;
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::unique_lock<std::mutex> lock_;
  std::vector<std::string> warnings_;
};

std::string meshNames(const aiScene& scene) {
  std::string names;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiString& name = scene.mMeshes[i]->mName;
    names += (names.empty() ? "'" : ", '") + (name.length ? std::string(name.C_Str()) : "mesh #" + std::to_string(i)) + "'";
  }
  return names;
}

// Assimp drops faces with out-of-range indices and only warns; refuse such a file instead.
void rejectDroppedIndices(const std::filesystem::path& model, const aiScene& scene, const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) {
    if (warning.find("out-of-range indices") == std::string::npos && warning.find("index out of range") == std::string::npos) {
      continue;
    }
    const std::string where = scene.mNumMeshes == 1 ? "mesh " + meshNames(scene) : "one of the meshes " + meshNames(scene);
    throw InputError(model.string() + ": " + where + ": indices out of range (" + warning + ")");
  }
}

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // Assimp is row-major with translation in the 4th column; GLM is column-major.
  return glm::transpose(glm::make_mat4(&m.a1));
}

scene::MeshData convertMesh(const aiMesh& mesh, unsigned index, scene::RepairCounters& repairs) {
  scene::MeshData out;
  out.name = mesh.mName.length ? mesh.mName.C_Str() : "mesh #" + std::to_string(index);
  out.positions.reserve(mesh.mNumVertices);
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    out.positions.emplace_back(mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z);
  }
  if (mesh.HasNormals()) {
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      out.normals.emplace_back(mesh.mNormals[v].x, mesh.mNormals[v].y, mesh.mNormals[v].z);
    }
  }
  if (mesh.HasTangentsAndBitangents() && mesh.HasNormals()) {
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const glm::vec3 t(mesh.mTangents[v].x, mesh.mTangents[v].y, mesh.mTangents[v].z);
      const glm::vec3 b(mesh.mBitangents[v].x, mesh.mBitangents[v].y, mesh.mBitangents[v].z);
      const float w = glm::dot(glm::cross(out.normals[v], t), b) < 0.0f ? -1.0f : 1.0f;
      out.tangents.emplace_back(t, w);
    }
  }
  if (mesh.HasTextureCoords(0)) {
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      out.uv0.emplace_back(mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y);
    }
  }
  out.indices.reserve(size_t(mesh.mNumFaces) * 3);
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) {
      ++repairs.nonTrianglePrimitives;
      continue;
    }
    out.indices.insert(out.indices.end(), {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
  }
  return out;
}

class SceneConverter {
 public:
  SceneConverter(const aiScene& source, std::filesystem::path file) : source_(source), file_(std::move(file)) {}

  scene::ImportedModel convert(const std::set<std::string>& opened) {
    std::set<std::string> dependencies = opened;
    MaterialConverter(source_, file_, scene_, dependencies).convertAll();
    convertMeshes();
    if (source_.mRootNode) visit(*source_.mRootNode, glm::mat4(1.0f), 0);
    scene::ImportedModel result;
    result.scene = std::move(scene_);
    // The model file itself is in the cache key already.
    dependencies.erase(file_.filename().string());
    result.dependencies.assign(dependencies.begin(), dependencies.end());
    return result;
  }

 private:
  void convertMeshes() {
    meshIndex_.assign(source_.mNumMeshes, -1);
    for (unsigned i = 0; i < source_.mNumMeshes; ++i) {
      const aiMesh& mesh = *source_.mMeshes[i];
      if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
        scene_.repairs.nonTrianglePrimitives += mesh.mNumFaces;  // a point cloud or line set
        continue;
      }
      scene::MeshData data = convertMesh(mesh, i, scene_.repairs);
      scene::repairMesh(data, scene_.repairs, file_.string());
      if (data.indices.empty()) {
        ++scene_.repairs.emptyMeshes;
        continue;
      }
      meshIndex_[i] = static_cast<int32_t>(scene::appendMesh(scene_, std::move(data)));
    }
  }

  void visit(const aiNode& node, const glm::mat4& parent, unsigned depth) {
    if (depth > kMaxNodeDepth) {
      throw InputError(file_.string() + ": node hierarchy deeper than " + std::to_string(kMaxNodeDepth) +
                       " levels (recursive nodes?) at node '" + node.mName.C_Str() + "'");
    }
    const glm::mat4 world = parent * toGlm(node.mTransformation);
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      const unsigned source = node.mMeshes[i];
      if (source >= source_.mNumMeshes) {
        throw InputError(file_.string() + ": node '" + node.mName.C_Str() + "' references mesh " +
                         std::to_string(source) + " of " + std::to_string(source_.mNumMeshes));
      }
      if (meshIndex_[source] < 0) continue;
      const unsigned material = std::min(source_.mMeshes[source]->mMaterialIndex,
                                         source_.mNumMaterials ? source_.mNumMaterials - 1 : 0u);
      scene::addInstance(scene_, static_cast<uint32_t>(meshIndex_[source]), material, world);
    }
    placeLightsAndCamera(node, world);
    for (unsigned c = 0; c < node.mNumChildren; ++c) visit(*node.mChildren[c], world, depth + 1);
  }

  void placeLightsAndCamera(const aiNode& node, const glm::mat4& world) {
    for (unsigned i = 0; i < source_.mNumLights; ++i) {
      const aiLight& light = *source_.mLights[i];
      if (light.mName != node.mName) continue;
      const glm::vec3 rgb(light.mColorDiffuse.r, light.mColorDiffuse.g, light.mColorDiffuse.b);
      const float intensity = std::max({rgb.r, rgb.g, rgb.b, 0.0f});
      if (!(intensity > 0.0f) || !std::isfinite(intensity)) continue;
      if (light.mType == aiLightSource_POINT || light.mType == aiLightSource_SPOT) {
        const glm::vec3 position(world * glm::vec4(light.mPosition.x, light.mPosition.y, light.mPosition.z, 1.0f));
        scene_.lights.push_back({position, rgb / intensity, intensity, 10.0f});
      } else if (light.mType == aiLightSource_DIRECTIONAL && !scene_.sun.enabled) {
        const glm::vec3 d(world * glm::vec4(light.mDirection.x, light.mDirection.y, light.mDirection.z, 0.0f));
        if (glm::length(d) > 0.0f) scene_.sun = {true, glm::normalize(d), rgb / intensity, intensity};
      }
    }
    if (scene_.hasCamera) return;
    for (unsigned i = 0; i < source_.mNumCameras; ++i) {
      const aiCamera& camera = *source_.mCameras[i];
      if (camera.mName != node.mName) continue;
      scene::Camera& c = scene_.camera;
      c.position = glm::vec3(world * glm::vec4(camera.mPosition.x, camera.mPosition.y, camera.mPosition.z, 1.0f));
      const glm::vec3 look(world * glm::vec4(camera.mLookAt.x, camera.mLookAt.y, camera.mLookAt.z, 0.0f));
      const glm::vec3 up(world * glm::vec4(camera.mUp.x, camera.mUp.y, camera.mUp.z, 0.0f));
      if (!(glm::length(look) > 0.0f) || !(camera.mClipPlaneNear > 0.0f) || camera.mClipPlaneFar <= camera.mClipPlaneNear) continue;
      c.target = c.position + glm::dvec3(glm::normalize(look));
      c.up = glm::length(up) > 0.0f ? glm::normalize(up) : glm::vec3(0, 1, 0);
      const float aspect = camera.mAspect > 0.0f ? camera.mAspect : 16.0f / 9.0f;
      // Assimp gives the horizontal half-angle.
      c.verticalFovDeg = glm::degrees(2.0f * std::atan(std::tan(camera.mHorizontalFOV) / aspect));
      c.nearPlane = camera.mClipPlaneNear;
      c.farPlane = camera.mClipPlaneFar;
      scene_.hasCamera = c.verticalFovDeg > 0.0f && c.verticalFovDeg < 179.0f;
      if (!scene_.hasCamera) c = scene::Camera{};
      return;
    }
  }

  const aiScene& source_;
  std::filesystem::path file_;
  scene::Scene scene_;
  std::vector<int32_t> meshIndex_;
};

}  // namespace

scene::ImportedModel importModel(const std::filesystem::path& model) {
  ScopedWarningCapture capture;
  Assimp::Importer importer;
  auto* io = new RecordingIoSystem(model.parent_path());  // owned by the importer
  importer.SetIOHandler(io);
  const aiScene* source = nullptr;
  try {
    source = importer.ReadFile(model.string(), kPostProcess);
  } catch (const std::exception& e) {
    throw InputError(model.string() + ": cannot import: " + oneLine(e.what()));
  }
  if (!source || !source->mRootNode || (source->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    const std::string why = oneLine(importer.GetErrorString());
    throw InputError(model.string() + ": cannot import: " + (why.empty() ? "unsupported, truncated or incomplete file" : why));
  }
  rejectDroppedIndices(model, *source, capture.warnings());
  const std::set<std::string> opened = io->opened();
  return SceneConverter(*source, model).convert(opened);
}

}  // namespace fgb::import
