// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): push blocks and flags of the forward path's
// mesh passes (src/renderer/features/meshes/): "Mesh Frustum Cull" (mesh_cull.comp,
// mesh_compact.comp) and the forward colour passes (forward.vert, forward.frag).
#ifndef FGB_RENDERER_SHARED_MESHES_H
#define FGB_RENDERER_SHARED_MESHES_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/debug.h"
#include "renderer/shared/opaque_depth.h"

#define FGB_MESH_CULL_GROUP_SIZE 64      // mesh_cull.comp: one instance each
#define FGB_MESH_COMPACT_GROUP_SIZE 256  // mesh_compact.comp: one workgroup per batch
#define FGB_MESH_BATCH_COUNT 3           // draw batches: opaque, alpha-masked, transparent (DrawClass)

FGB_GPU_BEGIN

// mesh_cull.comp.
struct MeshCullPush {
  uint frame;      // FrameConstants: the frustum planes
  uint instances;
  uint commands;
  uint visible;    // visible-instance list, grouped by draw group (firstInstance = group start)
  uint stats;      // [0] visible instances, [1] visible triangles
  uint instanceCount;
};
FGB_CHECK_PUSH(MeshCullPush, 24)

// mesh_compact.comp.
struct MeshCompactPush {
  uint commands;    // per draw group, instance counts filled by the cull dispatch
  uint drawList;    // packed commands: batch b's start at its first group's index
  uint drawCounts;  // [b]: commands of batch b in drawList
  uint stats;       // [2]: draws issued (all batches)
  uvec4 batches[FGB_MESH_BATCH_COUNT];  // x: first group, y: group count
};
FGB_CHECK_PUSH(MeshCompactPush, 64)

// The forward colour passes (forward.vert, forward.frag).
struct ForwardPush {
  uint frame;
  uint instances;
  uint visible;
  uint materials;
  uint lights;
  uint clusterCounts;   // FGB_NONE: no clustered lighting (loop over all lights)
  uint clusterIndices;
  uint materialSampler;
  uint flags;                   // kForwardTransparent, kForwardInjectNan, kForwardInjectBias
  OpaqueDepthTest opaqueDepth;  // visibility buffer, transparent pass: the depth test (forward.frag)
};
FGB_CHECK_PUSH(ForwardPush, 48)
const uint kForwardTransparent = 2u;  // the transparent pass
const uint kForwardInjectNan = 4u;    // debug.inject_nan names this pass: a NaN at the centre pixel
const uint kForwardInjectBias = 8u;   // debug.inject_bias names this pass: + kInjectedBias (debug.h)

FGB_GPU_END

#endif
