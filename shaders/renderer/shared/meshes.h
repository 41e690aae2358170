// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): push blocks and flags of the forward path's
// mesh passes (src/renderer/features/meshes/): "Mesh Frustum Cull" (mesh_cull.comp,
// mesh_compact.comp), "Transparent Cluster Cull" (transparent_cluster_cull.comp,
// transparent_cluster_pack.comp) and the forward colour passes (forward.vert, forward.frag).
#ifndef FGB_RENDERER_SHARED_MESHES_H
#define FGB_RENDERER_SHARED_MESHES_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/debug.h"
#include "renderer/shared/opaque_depth.h"

#define FGB_MESH_CULL_GROUP_SIZE 64      // mesh_cull.comp: one instance each
#define FGB_MESH_COMPACT_GROUP_SIZE 256  // mesh_compact.comp: one workgroup per batch
#define FGB_MESH_BATCH_COUNT 3           // draw batches: opaque, alpha-masked, transparent (DrawClass)
// transparent_cluster_cull.comp: one cluster entry each; a workgroup's entries are one chunk of
// the command list (transparent_cluster_pack.comp: one workgroup per chunk).
#define FGB_TRANSPARENT_CHUNK_SIZE 64

FGB_GPU_BEGIN

// mesh_cull.comp.
struct MeshCullPush {
  uint frame;      // FrameConstants: the frustum planes
  uint instances;
  uint commands;
  uint visible;    // visible-instance list, grouped by draw group (firstInstance = group start)
  uint stats;      // MeshCullStats (mesh_feature.hpp)
  uint instanceCount;
  uint firstTransparentGroup;  // groups from here on are transparent (their triangles: stats[3])
};
FGB_CHECK_PUSH(MeshCullPush, 28)

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
  uint flags;                   // kForward* bits
  OpaqueDepthTest opaqueDepth;  // visibility buffer, transparent pass: the depth test (forward.frag)
};
FGB_CHECK_PUSH(ForwardPush, 48)
const uint kForwardTransparent = 2u;  // the transparent pass
const uint kForwardInjectNan = 4u;    // debug.inject_nan names this pass: a NaN at the centre pixel
const uint kForwardInjectBias = 8u;   // debug.inject_bias names this pass: + kInjectedBias (debug.h)
// forward.vert: gl_InstanceIndex is the GPU instance itself, not a visible-list slot (the
// transparent cluster draws of "Transparent Cluster Cull").
const uint kForwardInstanceIsSlot = 16u;

// The transparent instances' LOD cut (the meshes feature's "lod" option; GpuScene's
// ClusterGeometry): each transparent mesh's clusters, every LOD level, are entries; an entry is
// one indexed draw of the cluster's triangles from the transparent cluster index buffer, which
// also holds the mesh's own index range (full detail, in the scene index buffer's order).
struct TransparentMeshClusters {
  vec4 groupBounds;  // mesh-local sphere holding the parent groups of every level-0 cluster
  uint firstEntry;   // into the TransparentClusterEntry list
  uint entryCount;   // 0: the mesh has no transparent instance
  int vertexOffset;  // the mesh's first vertex (indices are mesh-local, as in the scene's index buffer)
  uint firstIndex;   // the mesh's own triangles in the transparent cluster index buffer
  uint indexCount;
  float minParentError;  // the smallest parent-group error of its level-0 clusters (mesh-local)
  uint pad[2];
};
FGB_CHECK_SIZE(TransparentMeshClusters, 48)

struct TransparentClusterEntry {
  uint cluster;     // into the scene's clusters (ClusterData)
  uint firstIndex;  // its 3 * triangleCount indices in the transparent cluster index buffer
};
FGB_CHECK_SIZE(TransparentClusterEntry, 8)

// "Transparent Cluster Cull": entry k of transparent slot s is invocation s * entryStride + k (slot
// s is GPU instance firstSlot + s, in the frame's back-to-front order), so the chunks' draws, in
// chunk order, are in blend order. An instance whose whole cut is level 0 is one draw of the
// mesh's own index range (its entry 0), so it blends exactly as without LOD.
struct TransparentCullPush {
  uint frame;  // FrameConstants: frustum planes, projection (the LOD cut)
  uint instances;
  uint clusters;       // ClusterData[]
  uint meshes;         // TransparentMeshClusters per scene mesh
  uint entries;        // TransparentClusterEntry[]
  uint chunkCommands;  // DrawCommand per invocation: each chunk's kept draws first, then zeros
  uint chunkTotals;    // uvec4 per chunk: kept draws, of which whole meshes, their triangles
  uint packed;         // transparent_cluster_pack.comp: every chunk's kept draws, in chunk order
  uint drawCount;      // [0]: draws in `packed`
  uint stats;          // MeshCullStats: transparent clusters, whole meshes and triangles drawn
  uint firstSlot;
  uint slotCount;
  uint entryStride;  // the most entries of one transparent mesh
  uint chunkCount;
  // render.lod_error in scene pixels (times render.ssaa), > 0 (at 0 the raster pass draws the
  // index buffer's full detail instead of running this; the cluster form runs with 0: level 0).
  float lodThreshold;
  uint flags;  // kTransparentCull* bits
  // The cluster form: uvec3 indirect dispatch of one workgroup per kept draw, as (min(n, 32768),
  // ceil(n / 32768), 1) (transparent_cluster_pack.comp; "Transparent Raster"). FGB_NONE otherwise.
  uint dispatchArgs;
};
FGB_CHECK_PUSH(TransparentCullPush, 68)
// The cluster form, for the compute transparent passes (render.transparent=compute,
// renderer/shared/transparent.h): every kept entry is its cluster (no whole-mesh draws: the
// K-buffer sorts per pixel, so the index buffer's order no longer matters), and a draw's
// firstIndex holds the ClusterData index instead of its index-buffer start. At render.lod_error=0
// the cut is level 0 (lodInCut), the mesh's own triangles.
const uint kTransparentCullClusterIds = 1u;

FGB_GPU_END

#endif
