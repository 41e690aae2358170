// The scene as uploaded to the GPU (persistent RHI objects, alive for the whole run) and the
// per-frame render targets. Both travel through the blackboard.
#pragma once

#include "render_settings.hpp"
#include "renderer/shared/scene.h"

#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/types.hpp>
#include <fgb/scene/scene.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace fgb::features {

// Vertex attribute streams inside GpuScene::vertices (byte offsets).
struct VertexStreams {
  uint64_t positions = 0;  // vec3
  uint64_t normals = 0;    // vec3
  uint64_t tangents = 0;   // vec4
  uint64_t uvs = 0;        // vec2
};

// Which pipeline a draw group uses; also the order in which forward passes draw them.
enum class DrawClass : uint8_t { Opaque, Masked, Transparent };

// One indirect command: every instance of one mesh in one draw class (transparent instances get a
// group each, sorted back to front, so the multi-draw's command order is the blend order).
struct DrawGroup {
  uint32_t mesh = 0;
  DrawClass drawClass = DrawClass::Opaque;
  uint32_t firstSlot = 0;  // first entry in the visible-instance list (= firstInstance)
  uint32_t capacity = 0;   // instances in the group
};

// The cooked clusters, uploaded where the render path says so ("upload": {"clusters": true}: the
// visibility-buffer path), and one gpu::ClusterDraw per cluster of every opaque or alpha-masked
// instance ("Cluster Cull" tests each). Transparent instances stay with the hardware "Mesh Render
// Transparent", which with the meshes feature's "lod" option draws their LOD cut from the
// transparent meshes' clusters (TransparentClusters).
// Cluster vertices are numbered across the scene (cluster.firstVertex + local index): a vertex
// shared by several clusters has a copy in each, so a triangle's corners are found from its one
// packed word without the mesh's index buffer.
// The clusters of every mesh a transparent instance uses, every LOD level, as indexed draws
// ("Transparent Cluster Cull" keeps each transparent instance's LOD cut of them for "Mesh Render
// Transparent"): an index buffer holding each cluster's triangles as mesh-local indices (drawn
// with the mesh's first vertex as vertex offset, like the scene's index buffer), and which of them
// belong to which mesh.
struct TransparentClusters {
  rhi::BufferId indices;    // uint32, index usage: 3 per cluster triangle
  rhi::BufferId meshes;     // gpu::TransparentMeshClusters per scene mesh (no entries: no transparent instance)
  rhi::BufferId entries;    // gpu::TransparentClusterEntry per cluster of those meshes, mesh by mesh
  uint32_t maxEntries = 0;  // the most entries of one mesh (0: no transparent instance)
};

struct ClusterGeometry {
  rhi::BufferId clusters;         // scene::Cluster[] (mesh-local bounds, cones, triangle and vertex ranges)
  rhi::BufferId packedTriangles;  // uint32 per triangle: scene::packClusterTriangle (cluster-local)
  rhi::BufferId vertices;         // uvec4 per cluster vertex: position (float bits), its vertex in GpuScene::vertices
  rhi::BufferId draws;            // gpu::ClusterDraw[]
  // uvec2 per GPU instance: its first ClusterDraw and their number (every level's clusters; 0 for
  // a transparent instance). The draws are in instance order: one instance's are contiguous.
  rhi::BufferId instanceDraws;
  uint32_t drawCount = 0;
  uint64_t triangles = 0;  // triangles of all draws: the most "Triangle Filter" can keep
  TransparentClusters transparent;
};

// Executions of the frame graph that may be pending on the GPU at once (rhi::DeviceOptions), and
// so the copies of the per-frame values: execution e reads copy e % kFramesInFlight, which the
// host rewrites only once execution e - kFramesInFlight has completed.
inline constexpr uint32_t kFramesInFlight = 2;

// One frame in flight's copy of the values that change per frame: host-visible buffers the
// shaders read directly (indices: bindless storage-buffer indices, fixed for the buffer's life).
struct FrameBuffers {
  rhi::BufferId constants;        // gpu::FrameConstants (camera, frustum planes, simulation step)
  rhi::BufferId instances;        // gpu::Instance[] in render space, ordered by draw group
  rhi::BufferId lights;           // gpu::PointLight[] in render space (at least one entry)
  rhi::BufferId commandTemplate;  // gpu::DrawCommand[], instanceCount 0, transparent groups back to front
  uint32_t constantsIndex = 0;
  uint32_t instancesIndex = 0;
  uint32_t lightsIndex = 0;
};

struct GpuScene {
  const scene::Scene* scene = nullptr;
  rhi::BufferId vertices;          // all attribute streams (vertex + storage usage)
  VertexStreams streams;
  rhi::BufferId indices;           // uint32, mesh-local
  rhi::BufferId materials;         // gpu::Material[]
  rhi::BufferId exposure;          // gpu::Exposure (written by the "Exposure" node with auto exposure)
  // The per-frame values (camera, render-space instances and lights, transparent order), one
  // copy per frame in flight, written by the host before the frame's submit (frame_update.cpp).
  std::array<FrameBuffers, kFramesInFlight> frames;
  rhi::SamplerId materialSampler;
  rhi::SamplerId linearClampSampler;
  std::vector<rhi::TextureId> textures;
  std::vector<DrawGroup> groups;   // in command order: opaque, masked, transparent
  std::vector<uint32_t> instanceOrder;  // GPU instance i is scene instance instanceOrder[i]
  gpu::FrameConstants constants{};   // the still camera's constants (the grid and counts are every frame's)
  gpu::FrameConstants current{};     // the frame being recorded: what its copy of the constants holds
  ClusterGeometry clusterGeometry; // visibility-buffer path only
  uint32_t instanceCount = 0;
  uint32_t lightCount = 0;

  // Range of groups of one class: [first, first + count).
  [[nodiscard]] std::pair<uint32_t, uint32_t> groupRange(DrawClass drawClass) const;
  // The copy an execution of the frame graph reads: a job's recording depends on its slot only.
  [[nodiscard]] const FrameBuffers& frame(uint64_t execution) const { return frames[execution % kFramesInFlight]; }
};

// The frame's colour and depth targets. Forward passes draw into `color` (multisampled when
// samples > 1) at `extent`; "MSAA Resolve" (features/ssaa/msaa_resolve_feature.hpp), which the
// render path composes after the last of them, resolves it into `hdr` (single-sampled, `color` is
// `hdr`). Without SSAA, `hdr` is the imported HDR image; with render.ssaa = S > 1 it is a
// supersampled transient (S times the output size) until "SSAA Resolve" filters it into
// `outputHdr` (the imported image), after which `hdr` and `extent` are the output's, as bloom and
// tone mapping expect.
struct FrameTargets {
  graph::Extent extent{};        // size of the latest `hdr`: the scene passes' size, then the output's
  graph::Extent outputExtent{};  // the output (imported HDR and display images)
  uint32_t samples = 1;
  graph::TextureHandle color;  // latest version of the (MSAA) colour target
  graph::TextureHandle depth;  // latest version of the (MSAA) depth target
  // Visibility-buffer path: the opaque scene's depth, one float per pixel of `extent` in rows of
  // extent.width, written by "Material Shade"; the colour passes after it test against it in their
  // fragment shaders (DepthTest::OpaqueDepthBuffer) and `depth` is not used. Invalid on forward.
  graph::BufferHandle opaqueDepth;
  graph::TextureHandle hdr;    // the resolved HDR image; final once colorResolved is set
  graph::TextureHandle outputHdr;  // SSAA only: the imported HDR image "SSAA Resolve" writes
  graph::TextureHandle display;  // tone-mapped output (imported)
  graph::BufferHandle exposure;  // the exposure state, when a node writes it (auto exposure);
                                 // invalid with a fixed exposure (then it never changes)
  std::array<float, 4> background{};  // HDR clear colour: background radiance, pre-exposed
  bool colorResolved = false;    // "MSAA Resolve" was declared: no more colour passes, `hdr` is final
  bool colorCleared = false;     // the first colour pass clears colour
  bool depthCleared = false;     // the first pass using depth (maybe a depth prepass) clears it
};

inline constexpr graph::Format kHdrFormat = graph::Format::R16G16B16A16Sfloat;
inline constexpr graph::Format kDepthFormat = graph::Format::D32Sfloat;
// Reversed-Z (scene::projectionMatrix): depth 1 at the near plane, 0 at the far plane (or
// infinity). Depth clears to the far value and nearer fragments pass GREATER_OR_EQUAL.
inline constexpr float kDepthClear = 0.0f;
// Radiance behind every object (the open sky of the courtyards), before light scale and exposure.
inline constexpr std::array<float, 4> kBackgroundRadiance{0.02f, 0.025f, 0.035f, 1.0f};
inline constexpr rhi::CompareOp kDepthCompare = rhi::CompareOp::GreaterOrEqual;
inline constexpr graph::Format kDisplayFormat = graph::Format::R8G8B8A8Srgb;

}  // namespace fgb::features
