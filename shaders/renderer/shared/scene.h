// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the std430 structs of the scene every
// renderer shader reads (shaders/renderer/include/common.glsl declares their buffers; the renderer
// fills them in src/renderer/scene_workload/gpu_upload.cpp and frame_setup.cpp).
#ifndef FGB_RENDERER_SHARED_SCENE_H
#define FGB_RENDERER_SHARED_SCENE_H

#include "fgb/rhi/shared/prelude.h"

FGB_GPU_BEGIN

// Camera and view data of one frame, written by the host before each frame's submit into the copy
// of its frame in flight (src/renderer/scene_workload/frame_update.cpp): nothing that changes from
// frame to frame is baked into recorded commands.
struct FrameConstants {
  mat4 view;             // render space -> view space: the camera's rotation and its offset from
                         // the anchor (render space's origin, near the camera: render_space.hpp)
  mat4 proj;             // Vulkan clip space, Y flipped for a top-left origin; reversed-Z
                         // (near -> 1, far -> 0), the far plane possibly infinite
  mat4 viewProj;
  mat4 invProj;
  vec4 cameraPosition;   // xyz: the eye in render space (camera - anchor, small); w: 1
  vec4 sunDirection;     // xyz: direction light travels; w: 1 when enabled
  vec4 sunColor;         // rgb * intensity
  vec4 viewport;         // width, height, 1/width, 1/height
  vec4 depthRange;       // near, cluster far (finite), slice scale, slice bias (clusters)
  uvec4 clusterGrid;     // tiles x, tiles y, slices, tile size in pixels
  uvec4 counts;          // lights, instances, max lights per cluster, debug view
  vec4 ambient;          // rgb: constant ambient term (radiance, times the light scale)
  uvec4 buffers;         // x: storage-buffer index of the Exposure state
  vec4 frustumPlanes[6]; // render space, inside: dot(n, p) + d >= 0 (mesh and cluster culling)
  vec4 anchorOffset;     // xyz: the particles' anchor minus this frame's (particles live in the
                         // scene camera's render space: add this to render them)
  vec4 simulation;       // x: this frame's particle step, s (0: the particles hold still); y: path time, s
  uvec4 step;            // x: particle simulation step index; y: kFrame* flags
};
FGB_CHECK_SIZE(FrameConstants, 4 * 64 + 9 * 16 + 6 * 16 + 3 * 16)

// FrameConstants.step.y:
const uint kFrameHizValid = 1u;  // last frame left a HiZ pyramid (render.occlusion's phase 1 may test it)

// Exposure state (Frostbite's pre-exposure, "Moving Frostbite to PBR" 2014). Lighting, emissive,
// particles and the background are multiplied by preExposure before they are written to the R16F
// HDR target, so the stored values stay in range whatever the scene's absolute radiance; bloom's
// threshold is applied in the same pre-exposed units and tone mapping multiplies the HDR value by
// tonemapScale (= exposure / preExposure). Fixed exposure: preExposure = exposure = post.exposure,
// tonemapScale = 1, written once at upload. Auto exposure: the "Exposure" node measures the frame,
// writes exposure and tonemapScale for this frame's tone mapping and sets preExposure = exposure
// for the next frame.
struct Exposure {
  float preExposure;
  float tonemapScale;
  float exposure;
  float averageLuminance;  // scene-referred log-average luminance the exposure came from
};
FGB_CHECK_SIZE(Exposure, 16)

struct Instance {
  mat4 model;         // mesh -> render space (world minus the anchor)
  mat4 normalMatrix;  // inverse transpose of the model's 3x3, in a mat4
  vec4 boundsMin;     // render-space AABB
  vec4 boundsMax;
  uint material;
  uint drawGroup;     // index of the indirect command drawing this instance
  uint triangles;
  uint mesh;  // scene mesh ("Transparent Cluster Cull" finds a slot's clusters by it)
};
FGB_CHECK_SIZE(Instance, 176)

struct Material {
  vec4 baseColor;
  vec4 emissive;  // rgb * strength, w: normal scale
  float metallic;
  float roughness;
  float alphaCutoff;
  uint alphaMode;  // 0 opaque, 1 mask, 2 blend
  int baseColorTexture;  // bindless sampled-texture indices, -1: none
  int normalTexture;
  int metallicRoughnessTexture;
  int emissiveTexture;
};
FGB_CHECK_SIZE(Material, 64)

struct PointLight {
  vec4 positionRadius;  // render-space position
  vec4 color;           // rgb * intensity, w: 1 / radius (shading multiplies, see common.glsl)
};
FGB_CHECK_SIZE(PointLight, 32)

// VkDrawIndexedIndirectCommand.
struct DrawCommand {
  uint indexCount;
  uint instanceCount;
  uint firstIndex;
  int vertexOffset;
  uint firstInstance;
};
FGB_CHECK_SIZE(DrawCommand, 20)

FGB_GPU_END

#endif
