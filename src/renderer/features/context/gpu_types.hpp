// CPU mirrors of the std430 structs the renderer's shaders read (shaders/renderer/include/
// common.glsl). Keep field order and padding identical; the static_asserts catch size drift.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cstdint>

namespace fgb::features {

// Camera and view data, uploaded once per run (the benchmark camera does not move).
struct FrameConstantsGpu {
  glm::mat4 view{1.0f};      // camera-relative: a rotation only (render space -> view space)
  glm::mat4 proj{1.0f};      // Vulkan clip space, Y flipped for a top-left origin; reversed-Z
                             // (near -> 1, far -> 0), the far plane possibly infinite
  glm::mat4 viewProj{1.0f};
  glm::mat4 invProj{1.0f};
  glm::vec4 cameraPosition{0.0f};  // always (0, 0, 0, 1): render space is camera-relative
  glm::vec4 sunDirection{0.0f};  // xyz: direction light travels; w: 1 when enabled
  glm::vec4 sunColor{0.0f};      // rgb * intensity
  glm::vec4 viewport{0.0f};      // width, height, 1/width, 1/height
  glm::vec4 depthRange{0.0f};    // near, cluster far (finite), slice scale, slice bias (clusters)
  glm::uvec4 clusterGrid{0u};    // tiles x, tiles y, slices, tile size in pixels
  glm::uvec4 counts{0u};         // lights, instances, max lights per cluster, debug view
  glm::vec4 ambient{0.0f};       // rgb: constant ambient term (radiance, times the light scale)
  glm::uvec4 buffers{0u};        // x: storage-buffer index of the ExposureGpu state
};
static_assert(sizeof(FrameConstantsGpu) == 4 * 64 + 9 * 16);

// Exposure state (Frostbite's pre-exposure, "Moving Frostbite to PBR" 2014). Lighting, emissive,
// particles and the background are multiplied by preExposure before they are written to the R16F
// HDR target, so the stored values stay in range whatever the scene's absolute radiance; bloom's
// threshold is applied in the same pre-exposed units and tone mapping multiplies the HDR value by
// tonemapScale (= exposure / preExposure). Fixed exposure: preExposure = exposure = post.exposure,
// tonemapScale = 1, written once at upload. Auto exposure: the "Exposure" node measures the frame,
// writes exposure and tonemapScale for this frame's tone mapping and sets preExposure = exposure
// for the next frame.
struct ExposureGpu {
  float preExposure = 1.0f;
  float tonemapScale = 1.0f;
  float exposure = 1.0f;
  float averageLuminance = 0.0f;  // scene-referred log-average luminance the exposure came from
};
static_assert(sizeof(ExposureGpu) == 16);

struct InstanceGpu {
  glm::mat4 model{1.0f};         // mesh -> render space (world minus the camera position)
  glm::mat4 normalMatrix{1.0f};  // inverse transpose of the model's 3x3, in a mat4
  glm::vec4 boundsMin{0.0f};     // render-space AABB
  glm::vec4 boundsMax{0.0f};
  uint32_t material = 0;
  uint32_t drawGroup = 0;        // index of the indirect command drawing this instance
  uint32_t triangles = 0;
  uint32_t pad = 0;
};
static_assert(sizeof(InstanceGpu) == 176);

struct MaterialGpu {
  glm::vec4 baseColor{1.0f};
  glm::vec4 emissive{0.0f};      // rgb * strength, w: normal scale
  float metallic = 1.0f;
  float roughness = 1.0f;
  float alphaCutoff = 0.5f;
  uint32_t alphaMode = 0;        // 0 opaque, 1 mask, 2 blend
  int32_t baseColorTexture = -1; // bindless sampled-texture indices, -1: none
  int32_t normalTexture = -1;
  int32_t metallicRoughnessTexture = -1;
  int32_t emissiveTexture = -1;
};
static_assert(sizeof(MaterialGpu) == 64);

struct PointLightGpu {
  glm::vec4 positionRadius{0.0f};  // render-space position
  glm::vec4 color{0.0f};  // rgb * intensity, w: 1 / radius (shading multiplies, see common.glsl)
};
static_assert(sizeof(PointLightGpu) == 32);

// One cluster of one instance, for "Cluster Cull" (mirrors ClusterDraw in
// shaders/renderer/include/visbuffer.glsl).
struct ClusterDrawGpu {
  uint32_t instance = 0;     // GPU instance index
  uint32_t cluster = 0;      // index into the scene's clusters
  uint32_t firstVertex = 0;  // the mesh's first vertex (cluster indices are mesh-local)
  uint32_t flags = 0;        // ClusterDrawFlag bits
};
static_assert(sizeof(ClusterDrawGpu) == 16);

enum ClusterDrawFlag : uint32_t {
  kClusterSingleSided = 1,  // back faces are culled (glTF: not double-sided)
  kClusterMirrored = 2,     // negative determinant: front faces wind the other way on screen
  kClusterConeUsable = 4,   // near-uniform scale: the cluster's normal cone stays valid in world space
  kClusterAlphaMasked = 8,  // alpha-tested during "Visibility Raster"
};

// VkDrawIndexedIndirectCommand.
struct DrawIndexedCommand {
  uint32_t indexCount = 0;
  uint32_t instanceCount = 0;
  uint32_t firstIndex = 0;
  int32_t vertexOffset = 0;
  uint32_t firstInstance = 0;
};
static_assert(sizeof(DrawIndexedCommand) == 20);

}  // namespace fgb::features
