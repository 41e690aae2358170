// Mesh repair, normal/tangent generation and scene assembly.
#include <fgb/scene/geometry.hpp>

#include <fgb/core/error.hpp>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace fgb::scene {
namespace {

bool isFinite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool isFinite(const glm::vec4& v) { return isFinite(glm::vec3(v)) && std::isfinite(v.w); }

// Below this length a normal or tangent carries no direction worth keeping.
constexpr float kMinDirectionLength = 1e-12f;
// A triangle is "zero-area" when its height over the longest edge is below what float positions at
// its magnitude can resolve: a line or point up to rounding. Slivers (aspect 1e4 and more at
// sensible coordinates) stay well above this.
constexpr double kHeightUlps = 8.0 * 1.1920929e-7;  // 8 float epsilons of the largest coordinate

void validateIndices(const MeshData& mesh, const std::string& context) {
  if (mesh.indices.size() % 3 != 0) {
    throw InputError(context + ": mesh '" + mesh.name + "': index count " +
                     std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  }
  const size_t vertexCount = mesh.positions.size();
  for (size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= vertexCount) {
      throw InputError(context + ": mesh '" + mesh.name + "': index " + std::to_string(mesh.indices[i]) +
                       " at position " + std::to_string(i) + " is out of range (" +
                       std::to_string(vertexCount) + " vertices)");
    }
  }
}

// Drops attribute arrays whose length does not match the positions: they cannot be trusted.
void dropMismatchedAttributes(MeshData& mesh) {
  const size_t n = mesh.positions.size();
  if (mesh.normals.size() != n) mesh.normals.clear();
  if (mesh.tangents.size() != n) mesh.tangents.clear();
  if (mesh.uv0.size() != n) mesh.uv0.clear();
}

bool hasZeroArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 e0 = glm::dvec3(b) - glm::dvec3(a);
  const glm::dvec3 e1 = glm::dvec3(c) - glm::dvec3(a);
  const glm::dvec3 e2 = glm::dvec3(c) - glm::dvec3(b);
  const double longest = std::sqrt(std::max({glm::dot(e0, e0), glm::dot(e1, e1), glm::dot(e2, e2)}));
  if (longest == 0.0) return true;
  const double height = glm::length(glm::cross(e0, e1)) / longest;
  const glm::dvec3 magnitude = glm::max(glm::abs(glm::dvec3(a)), glm::max(glm::abs(glm::dvec3(b)), glm::abs(glm::dvec3(c))));
  const double resolution = kHeightUlps * std::max({magnitude.x, magnitude.y, magnitude.z, 1e-30});
  return height <= resolution;
}

// Keeps the triangles that can be rasterised; counts the others by reason.
void removeBadTriangles(MeshData& mesh, RepairCounters& repairs) {
  std::vector<bool> finite(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    finite[v] = isFinite(mesh.positions[v]);
    if (!finite[v]) ++repairs.nonFinitePositions;
  }
  size_t kept = 0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    if (!finite[i0] || !finite[i1] || !finite[i2]) {
      ++repairs.nonFiniteTriangles;
    } else if (i0 == i1 || i1 == i2 || i0 == i2) {
      ++repairs.degenerateTriangles;
    } else if (hasZeroArea(mesh.positions[i0], mesh.positions[i1], mesh.positions[i2])) {
      ++repairs.zeroAreaTriangles;
    } else {
      mesh.indices[kept++] = i0;
      mesh.indices[kept++] = i1;
      mesh.indices[kept++] = i2;
    }
  }
  mesh.indices.resize(kept);
}

// Renumbers vertices in first-use order and drops unreferenced ones (including any with a
// non-finite position, since no surviving triangle uses them).
void compactVertices(MeshData& mesh) {
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> remap(mesh.positions.size(), kUnused);
  uint32_t next = 0;
  for (uint32_t& index : mesh.indices) {
    if (remap[index] == kUnused) remap[index] = next++;
    index = remap[index];
  }
  if (next == mesh.positions.size()) {
    bool identity = true;
    for (uint32_t v = 0; v < next && identity; ++v) identity = remap[v] == v;
    if (identity) return;
  }
  auto compact = [&](auto& attribute) {
    if (attribute.empty()) return;
    std::remove_reference_t<decltype(attribute)> packed(next);
    for (size_t v = 0; v < remap.size(); ++v) {
      if (remap[v] != kUnused) packed[remap[v]] = attribute[v];
    }
    attribute = std::move(packed);
  };
  compact(mesh.positions);
  compact(mesh.normals);
  compact(mesh.tangents);
  compact(mesh.uv0);
}

void repairUvs(MeshData& mesh, RepairCounters& repairs) {
  for (glm::vec2& uv : mesh.uv0) {
    if (!isFinite(uv)) {
      uv = glm::vec2(0.0f);
      ++repairs.nonFiniteUvs;
    }
  }
}

void repairNormals(MeshData& mesh, RepairCounters& repairs) {
  if (mesh.normals.empty()) {
    ++repairs.generatedNormals;
    computeNormals(mesh);
    return;
  }
  std::vector<bool> bad(mesh.normals.size(), false);
  bool anyBad = false;
  for (size_t v = 0; v < mesh.normals.size(); ++v) {
    glm::vec3& n = mesh.normals[v];
    if (!isFinite(n)) {
      ++repairs.nonFiniteNormals;
      bad[v] = anyBad = true;
    } else if (float length = glm::length(n); !(length > kMinDirectionLength) || !std::isfinite(length)) {
      ++repairs.zeroNormals;
      bad[v] = anyBad = true;
    } else {
      n /= length;
    }
  }
  if (anyBad) computeNormals(mesh, bad);
}

void repairTangents(MeshData& mesh, RepairCounters& repairs) {
  if (mesh.tangents.empty()) {
    ++repairs.generatedTangents;
    computeTangents(mesh);
    return;
  }
  std::vector<bool> bad(mesh.tangents.size(), false);
  bool anyBad = false;
  for (size_t v = 0; v < mesh.tangents.size(); ++v) {
    glm::vec4& t = mesh.tangents[v];
    glm::vec3 xyz(t);
    if (!isFinite(t)) {
      ++repairs.nonFiniteTangents;
      bad[v] = anyBad = true;
      continue;
    }
    // Orthonormalise against the (already repaired) normal; a tangent parallel to it is useless.
    const glm::vec3& n = mesh.normals[v];
    xyz -= n * glm::dot(n, xyz);
    const float length = glm::length(xyz);
    if (!(length > 1e-6f)) {
      ++repairs.zeroTangents;
      bad[v] = anyBad = true;
      continue;
    }
    t = glm::vec4(xyz / length, t.w < 0.0f ? -1.0f : 1.0f);
  }
  if (anyBad) computeTangents(mesh, bad);
}

glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(helper, n));
}

}  // namespace

void computeNormals(MeshData& mesh, const std::vector<bool>& recompute) {
  const bool all = recompute.empty();
  std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    // The unnormalised cross product weights each face by its area.
    const glm::vec3 face = glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]);
    for (uint32_t i : {i0, i1, i2}) sum[i] += face;
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t v = 0; v < sum.size(); ++v) {
    if (!all && !recompute[v]) continue;
    const float length = glm::length(sum[v]);
    mesh.normals[v] = (length > 0.0f && std::isfinite(length)) ? sum[v] / length : glm::vec3(0, 1, 0);
  }
}

void computeTangents(MeshData& mesh, const std::vector<bool>& recompute) {
  const bool all = recompute.empty();
  const size_t n = mesh.positions.size();
  std::vector<glm::vec3> sSum(n, glm::vec3(0.0f)), tSum(n, glm::vec3(0.0f));
  if (!mesh.uv0.empty()) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
      const glm::vec3 e1 = mesh.positions[i[1]] - mesh.positions[i[0]];
      const glm::vec3 e2 = mesh.positions[i[2]] - mesh.positions[i[0]];
      const glm::vec2 d1 = mesh.uv0[i[1]] - mesh.uv0[i[0]];
      const glm::vec2 d2 = mesh.uv0[i[2]] - mesh.uv0[i[0]];
      const float det = d1.x * d2.y - d2.x * d1.y;
      if (!(std::abs(det) > 1e-20f)) continue;  // no UV parameterisation on this face
      const float r = 1.0f / det;
      const glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;
      const glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;
      if (!isFinite(sdir) || !isFinite(tdir)) continue;
      for (uint32_t k : i) {
        sSum[k] += sdir;
        tSum[k] += tdir;
      }
    }
  }
  mesh.tangents.resize(n);
  for (size_t v = 0; v < n; ++v) {
    if (!all && !recompute[v]) continue;
    const glm::vec3& normal = mesh.normals[v];
    glm::vec3 tangent = sSum[v] - normal * glm::dot(normal, sSum[v]);
    const float length = glm::length(tangent);
    if (!(length > 1e-12f) || !std::isfinite(length)) {
      mesh.tangents[v] = glm::vec4(anyPerpendicular(normal), 1.0f);
      continue;
    }
    tangent /= length;
    const float handedness = glm::dot(glm::cross(normal, tangent), tSum[v]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[v] = glm::vec4(tangent, handedness);
  }
}

void repairMesh(MeshData& mesh, RepairCounters& repairs, const std::string& context) {
  validateIndices(mesh, context);
  dropMismatchedAttributes(mesh);
  removeBadTriangles(mesh, repairs);
  compactVertices(mesh);
  repairUvs(mesh, repairs);
  repairNormals(mesh, repairs);
  repairTangents(mesh, repairs);
  if (mesh.uv0.empty()) mesh.uv0.assign(mesh.positions.size(), glm::vec2(0.0f));
}

int32_t addTexture(Scene& scene, Texture&& texture) {
  scene.textures.push_back(std::move(texture));
  return static_cast<int32_t>(scene.textures.size() - 1);
}

uint32_t addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

uint32_t appendMesh(Scene& scene, MeshData&& data) {
  Mesh mesh;
  mesh.name = std::move(data.name);
  mesh.firstVertex = static_cast<uint32_t>(scene.positions.size());
  mesh.vertexCount = static_cast<uint32_t>(data.positions.size());
  mesh.firstIndex = static_cast<uint32_t>(scene.indices.size());
  mesh.indexCount = static_cast<uint32_t>(data.indices.size());
  mesh.localBounds = Aabb::empty();
  for (const glm::vec3& p : data.positions) mesh.localBounds.extend(p);
  if (data.normals.size() != data.positions.size()) data.normals.assign(data.positions.size(), glm::vec3(0, 1, 0));
  if (data.tangents.size() != data.positions.size()) data.tangents.assign(data.positions.size(), glm::vec4(1, 0, 0, 1));
  if (data.uv0.size() != data.positions.size()) data.uv0.assign(data.positions.size(), glm::vec2(0.0f));
  scene.positions.insert(scene.positions.end(), data.positions.begin(), data.positions.end());
  scene.normals.insert(scene.normals.end(), data.normals.begin(), data.normals.end());
  scene.tangents.insert(scene.tangents.end(), data.tangents.begin(), data.tangents.end());
  scene.uv0.insert(scene.uv0.end(), data.uv0.begin(), data.uv0.end());
  scene.indices.insert(scene.indices.end(), data.indices.begin(), data.indices.end());
  scene.meshes.push_back(std::move(mesh));
  return static_cast<uint32_t>(scene.meshes.size() - 1);
}

uint32_t addInstance(Scene& scene, uint32_t mesh, uint32_t material, const glm::dmat4& transform) {
  Instance instance;
  instance.mesh = mesh;
  instance.material = material;
  instance.transform = transform;
  instance.worldBounds = scene.meshes.at(mesh).localBounds.transformed(transform);
  scene.instances.push_back(instance);
  return static_cast<uint32_t>(scene.instances.size() - 1);
}

void updateBounds(Scene& scene) {
  for (Mesh& mesh : scene.meshes) {
    mesh.localBounds = Aabb::empty();
    for (uint32_t v = 0; v < mesh.vertexCount; ++v) mesh.localBounds.extend(scene.positions[mesh.firstVertex + v]);
  }
  for (Instance& instance : scene.instances) {
    instance.worldBounds = scene.meshes.at(instance.mesh).localBounds.transformed(instance.transform);
  }
}

namespace {

// The uniform scale that best describes a transform (for light radii and particle sizes).
float uniformScale(const glm::dmat4& m) {
  return static_cast<float>(std::cbrt(std::abs(glm::determinant(glm::dmat3(m)))));
}

template <typename T>
void appendMoved(std::vector<T>& into, std::vector<T>& from) {
  into.insert(into.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

void shiftTexture(int32_t& index, int32_t offset) {
  if (index >= 0) index += offset;
}

}  // namespace

void mergeScene(Scene& into, Scene&& part, const glm::dmat4& placement) {
  const auto vertexOffset = static_cast<uint32_t>(into.positions.size());
  const auto indexOffset = static_cast<uint32_t>(into.indices.size());
  const auto meshOffset = static_cast<uint32_t>(into.meshes.size());
  const auto clusterOffset = static_cast<uint32_t>(into.clusters.size());
  const auto clusterTriangleOffset = static_cast<uint32_t>(into.clusterTriangles.size());
  const auto clusterVertexOffset = static_cast<uint32_t>(into.clusterVertices.size());
  const auto materialOffset = static_cast<uint32_t>(into.materials.size());
  const auto textureOffset = static_cast<int32_t>(into.textures.size());
  const float scale = uniformScale(placement);
  const glm::mat3 rotation = glm::mat3(glm::dmat3(placement));
  const auto place = [&](const glm::dvec3& p) { return glm::dvec3(placement * glm::dvec4(p, 1.0)); };

  appendMoved(into.positions, part.positions);
  appendMoved(into.normals, part.normals);
  appendMoved(into.tangents, part.tangents);
  appendMoved(into.uv0, part.uv0);
  appendMoved(into.indices, part.indices);  // mesh-local: no renumbering needed
  for (Cluster& cluster : part.clusters) {
    cluster.firstTriangle += clusterTriangleOffset;
    cluster.firstVertex += clusterVertexOffset;
  }
  appendMoved(into.clusters, part.clusters);
  appendMoved(into.clusterTriangles, part.clusterTriangles);  // cluster-local: no renumbering
  appendMoved(into.clusterVertices, part.clusterVertices);    // mesh-local too
  for (Mesh& mesh : part.meshes) {
    mesh.firstVertex += vertexOffset;
    mesh.firstIndex += indexOffset;
    mesh.firstCluster += clusterOffset;
  }
  appendMoved(into.meshes, part.meshes);
  for (Material& material : part.materials) {
    shiftTexture(material.baseColorTexture, textureOffset);
    shiftTexture(material.normalTexture, textureOffset);
    shiftTexture(material.metallicRoughnessTexture, textureOffset);
    shiftTexture(material.emissiveTexture, textureOffset);
  }
  appendMoved(into.materials, part.materials);
  appendMoved(into.textures, part.textures);
  for (Instance& instance : part.instances) {
    instance.mesh += meshOffset;
    instance.material += materialOffset;
    instance.transform = placement * instance.transform;
    instance.worldBounds = into.meshes[instance.mesh].localBounds.transformed(instance.transform);
  }
  appendMoved(into.instances, part.instances);
  for (PointLight& light : part.lights) {
    light.position = place(light.position);
    light.radius *= scale;
  }
  appendMoved(into.lights, part.lights);
  for (Emitter& emitter : part.emitters) {
    emitter.position = place(emitter.position);
    emitter.direction = glm::normalize(rotation * emitter.direction);
    emitter.sizeStart *= scale;
    emitter.sizeEnd *= scale;
  }
  appendMoved(into.emitters, part.emitters);
  if (!into.sun.enabled && part.sun.enabled) {
    into.sun = part.sun;
    into.sun.direction = glm::normalize(rotation * part.sun.direction);
  }
  if (!into.hasCamera && part.hasCamera) {
    into.camera = part.camera;
    into.camera.position = place(part.camera.position);
    into.camera.target = place(part.camera.target);
    into.camera.up = glm::normalize(rotation * part.camera.up);
    into.hasCamera = true;
  }
  into.repairs += part.repairs;
  appendMoved(into.warnings, part.warnings);
}

}  // namespace fgb::scene
