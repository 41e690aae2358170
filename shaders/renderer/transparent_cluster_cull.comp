#version 460
// "Transparent Cluster Cull", first dispatch: one invocation per cluster entry of each transparent
// slot (entry k of slot s is invocation s * entryStride + k; slot s is GPU instance firstSlot + s,
// the frame's back-to-front order). An entry is kept when its instance's box and its cluster's
// sphere meet the frustum and the cluster is in the instance's LOD cut (include/clusters.glsl's
// tests, the same as "Cluster Cull"'s; no normal-cone test: the transparent pipeline culls no
// faces). An instance whose cut is surely level 0 throughout is instead one draw of the mesh's own
// index range from its entry 0: blending depends on the order of an instance's triangles, and
// that is the index buffer's, the image without LOD. Each workgroup (a chunk) writes its kept
// draws first, in invocation order, then zero draws up to its size, and its totals: the chunk's
// draws are already a valid multi-draw in blend order (devices without
// vkCmdDrawIndexedIndirectCount draw them as they are), which transparent_cluster_pack.comp packs.
// With kTransparentCullClusterIds (render.transparent=compute) every kept entry is a cluster draw
// naming its cluster (renderer/shared/meshes.h).
#extension GL_GOOGLE_include_directive : require
#include "include/transparent_clusters.glsl"

// Whether every level-0 cluster's parent group projects above the threshold, so the cut is the
// mesh's own triangles: a lower bound of each of those projections (scene pixels), from the
// smallest of their errors at the farthest point of a sphere holding all of their spheres
// (projectedError divides by the distance to a group sphere's nearest point, which is nearer).
// Conservative: an instance this misses draws its level-0 clusters, the same triangles.
bool wholeMeshInCut(TransparentMeshClusters mesh, mat4 model, float scale, uint frame) {
  vec3 center = (model * vec4(mesh.groupBounds.xyz, 1.0)).xyz;
  float farthest = length(center - fgbFrames[frame].frame.cameraPosition.xyz) + mesh.groupBounds.w * scale;
  return mesh.minParentError * scale * pixelsPerUnit(frame) > pc.lodThreshold * farthest;
}

// The indexed draw of entry `entry` of transparent slot `slot` (indexCount 0: none); `whole`: it
// draws the mesh's own index range.
DrawCommand entryDraw(uint slot, uint entry, out bool whole) {
  const DrawCommand none = DrawCommand(0u, 0u, 0u, 0, 0u);
  whole = false;
  if (slot >= pc.slotCount) return none;
  const uint frame = pc.frame;
  const uint instanceId = pc.firstSlot + slot;
  Instance inst = fgbInstances[pc.instances].instances[instanceId];
  TransparentMeshClusters mesh = transparentMeshes[pc.meshes].meshes[inst.mesh];
  if (entry >= mesh.entryCount || !boxInside(frame, inst.boundsMin.xyz, inst.boundsMax.xyz)) return none;
  float scale = maxScale(inst.model);
  const bool clusterIds = (pc.flags & kTransparentCullClusterIds) != 0u;
  // firstInstance is the GPU instance itself: forward.vert reads it directly (kForwardInstanceIsSlot).
  if (!clusterIds && wholeMeshInCut(mesh, inst.model, scale, frame)) {
    whole = entry == 0u;
    return whole ? DrawCommand(mesh.indexCount, 1u, mesh.firstIndex, mesh.vertexOffset, instanceId) : none;
  }
  TransparentClusterEntry target = transparentEntries[pc.entries].entries[mesh.firstEntry + entry];
  ClusterData cluster = visClusters[pc.clusters].clusters[target.cluster];
  if (!lodInCut(cluster, inst.model, scale, frame, pc.lodThreshold)) return none;
  if (!sphereInside(frame, (inst.model * vec4(cluster.sphere.xyz, 1.0)).xyz, cluster.sphere.w * scale)) return none;
  return DrawCommand(3u * cluster.triangleCount, 1u, clusterIds ? target.cluster : target.firstIndex, mesh.vertexOffset,
                     instanceId);
}

void main() {
  const uint chunk = chunkIndex();
  if (chunk >= pc.chunkCount) return;  // the whole workgroup: the scan's barriers stay uniform
  const uint lane = gl_LocalInvocationID.x;
  const uint id = chunk * CHUNK + lane;
  bool whole;
  DrawCommand draw = entryDraw(id / pc.entryStride, id % pc.entryStride, whole);
  const bool kept = draw.indexCount > 0u;
  // Kept draws (bits 0-7, at most CHUNK) and those of whole meshes (bits 8-15).
  const uint mine = (kept ? 1u : 0u) | (whole ? 1u << 8 : 0u);
  const uint position = workgroupInclusiveSum(mine) & 0xffu;
  const uint draws = scan[CHUNK - 1u];
  barrier();  // every invocation read the totals before workgroupSum writes the scan memory
  const uint triangles = workgroupSum(draw.indexCount / 3u);
  const uint keptCount = draws & 0xffu;
  const uint base = chunk * CHUNK;
  if (kept) fgbCommands[pc.chunkCommands].commands[base + position - 1u] = draw;
  if (lane >= keptCount) fgbCommands[pc.chunkCommands].commands[base + lane] = DrawCommand(0u, 0u, 0u, 0, 0u);
  if (lane == 0u) chunkTotals[pc.chunkTotals].totals[chunk] = uvec4(keptCount, draws >> 8, triangles, 0u);
}
