// "Transparent Cluster Cull" (transparent_cluster_cull.comp, transparent_cluster_pack.comp): the
// buffers of the transparent instances' LOD cut (structs in renderer/shared/meshes.h) and the
// workgroup scan both dispatches use. The chunks are the dispatch's workgroups in the flat
// (slot, entry) order; a chunk index past 65535 groups spills into gl_WorkGroupID.y.
#ifndef FGB_RENDERER_TRANSPARENT_CLUSTERS_GLSL
#define FGB_RENDERER_TRANSPARENT_CLUSTERS_GLSL

#include "clusters.glsl"
#include "renderer/shared/meshes.h"

#define CHUNK FGB_TRANSPARENT_CHUNK_SIZE
layout(local_size_x = CHUNK) in;

layout(push_constant) uniform Push { TransparentCullPush pc; };

FGB_READONLY_STORAGE_BUFFER(TransparentMeshBlock, transparentMeshes) {
  TransparentMeshClusters meshes[];
} transparentMeshes[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(TransparentEntryBlock, transparentEntries) {
  TransparentClusterEntry entries[];
} transparentEntries[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(ChunkTotalBlock, chunkTotals, ) { uvec4 totals[]; } chunkTotals[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(ChunkTotalReadBlock, chunkTotalsRead) { uvec4 totals[]; } chunkTotalsRead[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(CommandReadBlock, fgbCommandsRead) { DrawCommand commands[]; } fgbCommandsRead[FGB_MAX_STORAGE_BUFFERS];

uint chunkIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

shared uint scan[CHUNK];

// Inclusive prefix sum of `value` over the workgroup (Hillis-Steele: CHUNK is small). Every
// invocation must call it.
uint workgroupInclusiveSum(uint value) {
  const uint lane = gl_LocalInvocationID.x;
  scan[lane] = value;
  barrier();
  for (uint offset = 1u; offset < CHUNK; offset <<= 1u) {
    uint add = lane >= offset ? scan[lane - offset] : 0u;
    barrier();
    scan[lane] += add;
    barrier();
  }
  return scan[lane];
}

// The sum of `value` over the workgroup, in every invocation (which must all call it).
uint workgroupSum(uint value) {
  workgroupInclusiveSum(value);
  const uint total = scan[CHUNK - 1u];
  barrier();  // every invocation read the total before the scan memory is written again
  return total;
}

#endif
