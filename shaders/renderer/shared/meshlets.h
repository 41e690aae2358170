// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the meshlet path's push blocks, flags and
// sizes (src/renderer/features/meshlets/, shaders/renderer/meshlets/). The clusters themselves
// are the visibility buffer's (renderer/shared/visbuffer.h: ClusterData, ClusterDraw).
#ifndef FGB_RENDERER_SHARED_MESHLETS_H
#define FGB_RENDERER_SHARED_MESHLETS_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/meshes.h"

// Workgroup sizes (the shaders' local_size_x; the feature sizes its task draws with them).
#define FGB_MESHLET_CULL_GROUP_SIZE 64  // meshlet_instance_cull.comp: one instance each
#define FGB_MESHLET_TASK_GROUP_SIZE 32  // meshlet.task: one cluster draw each; emits up to this many mesh groups
#define FGB_MESHLET_MESH_GROUP_SIZE 64  // meshlet.mesh: one cluster (<= 128 vertices and triangles) per workgroup
#define FGB_MESHLET_MAX_VERTICES 128    // a cooked cluster's limits (meshopt_buildMeshlets' in the cooker)
#define FGB_MESHLET_MAX_TRIANGLES 128

FGB_GPU_BEGIN

// One task draw (VkDrawMeshTasksIndirectCommandEXT plus the instance it draws): written by
// "Meshlet Instance Cull" after a 16-byte header whose first word is the draw count, read by
// "Meshlet Render"'s drawMeshTasksIndirectCount and (instance) by the task shader at gl_DrawID.
struct MeshletTaskCommand {
  uint groupCountX;  // task workgroups: ceil(the instance's cluster draws / FGB_MESHLET_TASK_GROUP_SIZE)
  uint groupCountY;
  uint groupCountZ;
  uint instance;  // GPU instance slot (its cluster draws: MeshletPush::ranges)
};
FGB_CHECK_SIZE(MeshletTaskCommand, 16)

// Statistics the culling stages add to (read back after the frame).
struct MeshletStats {
  uint instancesVisible;     // "Meshlet Instance Cull": instances inside the frustum (task draws)
  uint clustersVisible;      // task shader: clusters in the LOD cut, the frustum and facing the eye
  uint trianglesRasterised;  // mesh shader: triangles not culled (back-facing, zero-area, small, outside)
  uint trianglesTested;      // mesh shader: the visible clusters' triangles
  // render.occlusion: clusters phase 1 held back behind last frame's HiZ, and of those the ones
  // phase 2 found visible against this frame's.
  uint occluded;
  uint recovered;
  uint reserved[2];
};
FGB_CHECK_SIZE(MeshletStats, 32)

// "Meshlet Instance Cull" (meshlet_instance_cull.comp).
struct MeshletCullPush {
  uint frame;  // FrameConstants: the frustum planes
  uint instances;
  uint ranges;    // uvec2 per GPU instance slot: first cluster draw, cluster draws (0: transparent)
  uint commands;  // header (draw count) + MeshletTaskCommand[]
  uint stats;     // MeshletStats
  uint instanceCount;
};
FGB_CHECK_PUSH(MeshletCullPush, 24)

// "Meshlet Render" (meshlet.task, meshlet.mesh; forward.frag reads `shading`, at offset 0, as its
// own push block ForwardPush: the same shading as forward's "Mesh Render").
struct MeshletPush {
  ForwardPush shading;
  uint draws;      // ClusterDraw[]
  uint clusters;   // ClusterData[]
  uint triangles;  // packed cluster triangles
  uint positions;  // cluster vertex stream (uvec4: position bits, w: vertex in `vertices`)
  uint vertices;   // the scene's attribute streams, at these float offsets:
  uint normals;
  uint tangents;
  uint uvs;
  uint commands;       // MeshletTaskCommand[] (after the header): the task shader reads its instance
  uint ranges;         // as MeshletCullPush::ranges
  uint stats;          // MeshletStats
  uint flags;          // kMeshlet* bits; the MSAA sample count in kMeshletSamplesShift's bits
  float lodThreshold;  // render.lod_error in scene pixels (times render.ssaa); 0: level 0 only
  uint occlusion;      // render.occlusion: HiZ pyramid (low 16 bits), occlusion candidates (high 16 bits)
};
FGB_CHECK_PUSH(MeshletPush, 104)
// MeshletPush::flags:
const uint kMeshletSmallTriangles = 1u;  // cull triangles covering no sample (a pixel centre at MSAA 1)
const uint kMeshletOcclusion = 2u;       // phase 1: clusters last frame's HiZ hides become candidates
const uint kMeshletLate = 4u;            // phase 2: the candidates, tested against this frame's HiZ
const uint kMeshletReversedZ = 8u;       // the depth keys' convention
const uint kMeshletHoldBackOdd = 16u;    // debug.occlusion_hold_back: phase 1 also holds back odd draws
const uint kMeshletSamplesShift = 8u;    // flags >> 8: samples per pixel (1, 2, 4, 8: the standard pattern)

// The header before the task commands: its first word is the draw count.
#define FGB_MESHLET_COMMANDS_OFFSET 16

// render.occlusion's phase 2 arguments (meshlet_late_args.comp): from the candidate count (the
// first word of the candidate list, whose ClusterDraw indices follow), one task draw over them.
struct MeshletLateArgsPush {
  uint candidates;
  uint commands;  // header (draw count 0 or 1) + one MeshletTaskCommand
};
FGB_CHECK_PUSH(MeshletLateArgsPush, 8)

FGB_GPU_END

#endif
