// The cooked, GPU-ready scene: what the renderer consumes.
//
// Layout (all arrays are tightly packed, little-endian, float unless noted):
//   * Vertex attributes live in shared arrays, one entry per vertex: positions (vec3), normals
//     (vec3, unit length), tangents (vec4: xyz unit, w = handedness ±1), uv0 (vec2).
//   * indices (uint32) are MESH-LOCAL: draw mesh m with
//       vkCmdDrawIndexed(indexCount, instances, firstIndex, vertexOffset = firstVertex, ...).
//   * Every index triple is a valid, non-degenerate, finite triangle (see RepairCounters).
//   * Instances reference a mesh and a material; transforms map mesh-local to world space and may
//     be non-uniformly scaled (use the inverse transpose for normals). worldBounds is the AABB of
//     the transformed localBounds.
//   * World-space placement (instance transforms, bounds, light, emitter and camera positions) is
//     double precision: a scene may sit 1e7 m from the origin, where float steps by 1 m. Vertex
//     data stays float (mesh-local). The renderer subtracts an anchor near the camera in double and
//     sends everything to the GPU relative to it (src/renderer/features/context/render_space.hpp).
//   * Materials are glTF metallic-roughness; a texture index of -1 means "no texture".
//   * Textures are RGBA8 with a full mip chain down to 1x1, level 0 first, tightly packed.
// Cooked scenes come from loadScene() (load.hpp); stats() (stats.hpp) summarises one.
#pragma once

#include <fgb/scene/camera_path.hpp>

#include <glm/ext/matrix_double4x4.hpp>
#include <glm/ext/vector_double3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fgb::scene {

struct Aabb {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};

  // An "empty" box that any extend() replaces.
  static Aabb empty();
  bool isEmpty() const { return min.x > max.x; }
  void extend(const glm::dvec3& point);
  void extend(const Aabb& other);
  Aabb transformed(const glm::dmat4& transform) const;
};

struct Mesh {
  std::string name;
  uint32_t firstVertex = 0;
  uint32_t vertexCount = 0;
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;  // a multiple of 3
  Aabb localBounds;
  // This mesh's clusters, every LOD level: Scene::clusters[firstCluster, + clusterCount). The
  // first baseClusterCount (level 0) hold exactly the mesh's triangles; the rest are its
  // simplified levels (cook.cpp: the LOD DAG).
  uint32_t firstCluster = 0;
  uint32_t clusterCount = 0;
  uint32_t baseClusterCount = 0;
  uint32_t triangleCount() const { return indexCount / 3; }
};

// At most this many triangles per cluster (Nanite's and meshoptimizer's usual size).
inline constexpr uint32_t kClusterMaxTriangles = 128;
inline constexpr uint32_t kClusterMaxVertices = 128;

// The error a cluster that is never replaced (a root of the LOD DAG) has as its parent's: above
// every threshold.
inline constexpr float kLodRootError = 3.0e38f;

// A cluster (meshlet) of one mesh, cooked by meshopt_buildMeshlets for the visibility-buffer path.
// Bounds and cone are mesh-local. The cone follows meshoptimizer: the whole cluster faces away from
// a viewer at `eye` when dot(center - eye, coneAxis) >= coneCutoff * |center - eye| + radius.
//
// LOD (Karis 2021, "Nanite"): clusters form a DAG of groups. A group of clusters of a level is
// merged, simplified to about half with its outer border locked and split again into clusters of
// the next level, which replace the whole group at once. Each cluster carries the group that made
// it (lodCenter/lodRadius/lodError: its own bounds and error at level 0, where lodError is 0) and
// the group it is a member of (parent*: the group that replaces it; kLodRootError when none).
// Errors are mesh-local distances, monotonic up the DAG (a group's error is at least its members'
// and its sphere holds theirs), so one threshold on their projection picks one consistent cut: a
// cluster is drawn when its own error passes and its parent's does not (inLodCut).
struct Cluster {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
  glm::vec3 coneAxis{0.0f};
  float coneCutoff = 1.0f;  // cos of the cone's half angle widened by 90 degrees; 1: never culled
  uint32_t firstTriangle = 0;  // into Scene::clusterTriangles: one packed triangle each
  uint32_t triangleCount = 0;
  uint32_t firstVertex = 0;  // into Scene::clusterVertices: the cluster's own vertex list
  uint32_t vertexCount = 0;  // at most kClusterMaxVertices
  glm::vec3 lodCenter{0.0f};  // the group that made this cluster (its own sphere at level 0)
  float lodRadius = 0.0f;
  glm::vec3 parentCenter{0.0f};  // the group this cluster is a member of (its own group when a root)
  float parentRadius = 0.0f;
  float lodError = 0.0f;              // mesh-local distance; 0 at level 0
  float parentError = kLodRootError;  // >= lodError, > 0
  uint32_t lodLevel = 0;              // 0: the mesh's own triangles
  uint32_t pad = 0;
};
static_assert(sizeof(Cluster) == 96);

// Whether a cluster belongs to the cut of a (mesh-local, unprojected) error threshold: the same
// rule the GPU applies to projected errors ("Cluster Cull"). Every threshold >= 0 covers the mesh
// exactly once; 0 is level 0, the mesh's own triangles.
inline bool inLodCut(const Cluster& cluster, float threshold) {
  return cluster.lodError <= threshold && cluster.parentError > threshold;
}

// A cluster triangle: three 8-bit indices into its cluster's vertex list (corner k in bits
// 8k..8k+7), so the visibility-buffer shaders load one word per triangle and find its vertices at
// cluster.firstVertex + local index, with no mesh index buffer in between.
inline uint32_t packClusterTriangle(uint32_t a, uint32_t b, uint32_t c) {
  return a | (b << 8) | (c << 16);
}
inline uint32_t clusterTriangleCorner(uint32_t packed, uint32_t corner) {
  return (packed >> (8 * corner)) & 0xffu;
}

struct Instance {
  uint32_t mesh = 0;
  uint32_t material = 0;
  glm::dmat4 transform{1.0};
  Aabb worldBounds;
};

enum class AlphaMode : uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};  // linear RGBA
  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;
  glm::vec3 emissiveFactor{0.0f};   // linear RGB, multiplied by emissiveStrength
  float emissiveStrength = 1.0f;
  float normalScale = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;         // used when alphaMode == Mask
  bool doubleSided = false;
  int32_t baseColorTexture = -1;          // sRGB
  int32_t normalTexture = -1;             // linear, tangent space, +Y up (glTF convention)
  int32_t metallicRoughnessTexture = -1;  // linear: G = roughness, B = metallic
  int32_t emissiveTexture = -1;           // sRGB
};

struct MipLevel {
  uint32_t width = 0;
  uint32_t height = 0;
  uint64_t offset = 0;  // byte offset into Texture::data; size = width * height * 4
};

struct Texture {
  std::string name;  // source path, "embedded:<n>", "generated:<what>" or "fallback:<missing path>"
  uint32_t width = 0;
  uint32_t height = 0;
  bool srgb = false;
  std::vector<MipLevel> mips;       // level 0 = width x height, last = 1x1
  std::vector<uint8_t> data;        // RGBA8 texels of every level
};

struct PointLight {
  glm::dvec3 position{0.0};
  glm::vec3 color{1.0f};  // linear RGB
  float intensity = 1.0f; // candela-like scale, multiplied into color
  float radius = 10.0f;   // attenuation max(1 - d/R, 0) / d^2 reaches zero at R
};

struct DirectionalLight {
  bool enabled = false;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // direction the light travels, unit length
  glm::vec3 color{1.0f};
  float intensity = 0.0f;
};

struct Emitter {
  std::string name;
  glm::dvec3 position{0.0};
  float rate = 100.0f;                // particles per second
  float lifetime = 1.0f;              // seconds
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // cone axis, unit length
  float coneAngleDeg = 20.0f;         // half-angle of the velocity cone
  float speedMin = 0.5f;
  float speedMax = 1.0f;
  glm::vec4 colorStart{1.0f, 0.6f, 0.2f, 1.0f};  // linear RGBA at birth (rgb may exceed 1: HDR)
  glm::vec4 colorEnd{0.3f, 0.05f, 0.0f, 0.0f};   // at death
  float sizeStart = 0.1f;
  float sizeEnd = 0.02f;
  uint32_t maxParticles = 4096;
  uint32_t seed = 1;
};

struct Camera {
  glm::dvec3 position{0.0, 1.7, 5.0};
  glm::dvec3 target{0.0, 1.7, 0.0};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float verticalFovDeg = 60.0f;
  float nearPlane = 0.1f;
  float farPlane = 500.0f;
};

struct BloomSettings {
  bool enabled = true;
  float threshold = 1.0f;
  float knee = 0.5f;       // soft-threshold knee, as a fraction of the threshold
  float intensity = 0.05f; // compose weight
  float radius = 1.0f;     // upsample filter radius, in texels of each level
};

struct PostSettings {
  float exposure = 0.6f;      // tone mapping L = 1 - exp(-L_hdr * exposure); also the pre-exposure
  bool autoExposure = false;  // post.exposure=auto: exposure from the frame's average log luminance
  float lightScale = 1.0f;    // scene.light_scale, already applied to lights, emissive and bloom
                              // threshold; the renderer scales the background radiance by it
  BloomSettings bloom;
};

// Every repair made while importing or generating, so a report can list them.
struct RepairCounters {
  uint64_t nonFinitePositions = 0;    // vertices with NaN/Inf position, dropped
  uint64_t nonFiniteTriangles = 0;    // triangles using such a vertex, removed
  uint64_t nonFiniteNormals = 0;      // NaN/Inf normals, recomputed
  uint64_t zeroNormals = 0;           // zero-length normals, recomputed
  uint64_t nonFiniteTangents = 0;     // NaN/Inf tangents, recomputed
  uint64_t zeroTangents = 0;          // zero-length tangents, recomputed
  uint64_t nonFiniteUvs = 0;          // NaN/Inf texture coordinates, set to 0
  uint64_t degenerateTriangles = 0;   // triangles repeating an index, removed
  uint64_t zeroAreaTriangles = 0;     // distinct indices but (numerically) no area, removed
  uint64_t nonTrianglePrimitives = 0; // points and lines, skipped
  uint64_t generatedNormals = 0;      // meshes that had no normals
  uint64_t generatedTangents = 0;     // meshes that had no tangents
  uint64_t missingTextures = 0;       // replaced by the fallback texture
  uint64_t emptyMeshes = 0;           // meshes with no triangle left, dropped

  uint64_t total() const;
  RepairCounters& operator+=(const RepairCounters& other);
  bool operator==(const RepairCounters&) const = default;
};

struct Scene {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uv0;
  std::vector<uint32_t> indices;
  std::vector<Cluster> clusters;         // every mesh's clusters, in mesh order
  std::vector<uint32_t> clusterTriangles;  // packClusterTriangle; the same triangles as `indices`
  std::vector<uint32_t> clusterVertices;   // per cluster vertex: the mesh-local vertex it is

  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;  // never empty once cooked: index 0 may be the default
  std::vector<Texture> textures;

  std::vector<PointLight> lights;
  DirectionalLight sun;
  std::vector<Emitter> emitters;
  Camera camera;
  bool hasCamera = false;  // false: the loader fits a camera to the bounds
  // camera.path of the scene file (empty: a still camera). The renderer flies it; `camera` is the
  // still view (camera.path=none), whose position is also the origin of the particles' space.
  CameraPath cameraPath;
  // camera.time: the renderer shows the path's view at this time and holds it. Particles are
  // simulated up to it with the run's fixed time step and then hold still, so the frame equals
  // the path's frame at that time. Unset: a still view's particles advance one step per frame.
  std::optional<double> stillTime;
  PostSettings post;

  RepairCounters repairs;
  std::vector<std::string> warnings;  // one line each, e.g. a missing texture by name

  Aabb bounds() const;  // union of instance world bounds (empty box when no instances)
};

}  // namespace fgb::scene
