#version 460
// "Transparent Cluster Cull", second dispatch (after a barrier in the same node): one workgroup
// per chunk copies the chunk's kept draws to `packed` at the sum of the kept draws of the chunks
// before it, so `packed` holds every kept draw in blend order (back to front across instances) for
// one vkCmdDrawIndexedIndirectCount. The last chunk's workgroup writes the draw count and the
// statistics. Each workgroup sums the totals before it itself (no third dispatch): chunks^2 / 2
// loads in all, about 200 thousand for the atrium at atrium.scale=32.
#extension GL_GOOGLE_include_directive : require
#include "include/transparent_clusters.glsl"

void main() {
  const uint chunk = chunkIndex();
  if (chunk >= pc.chunkCount) return;
  const uint lane = gl_LocalInvocationID.x;
  const bool last = chunk + 1u == pc.chunkCount;
  // The last chunk sums every chunk (the frame's totals); the others only those before them.
  const uint summed = last ? pc.chunkCount : chunk;
  uvec4 all = uvec4(0u);
  uint before = 0u;
  for (uint j = lane; j < summed; j += CHUNK) {
    uvec4 totals = chunkTotalsRead[pc.chunkTotals].totals[j];
    all += totals;
    if (j < chunk) before += totals.x;
  }
  const uint start = workgroupSum(before);
  const uint own = chunkTotalsRead[pc.chunkTotals].totals[chunk].x;
  if (lane < own)
    fgbCommands[pc.packed].commands[start + lane] = fgbCommandsRead[pc.chunkCommands].commands[chunk * CHUNK + lane];
  if (!last) return;
  const uint draws = workgroupSum(all.x);
  const uint wholeMeshes = workgroupSum(all.y);
  const uint triangles = workgroupSum(all.z);
  if (lane == 0u) {
    fgbUints[pc.drawCount].values[0] = draws;
    fgbUints[pc.stats].values[4] = draws - wholeMeshes;  // MeshCullStats::transparentClusters
    fgbUints[pc.stats].values[5] = triangles;            // MeshCullStats::transparentClusterTriangles
    fgbUints[pc.stats].values[6] = wholeMeshes;          // MeshCullStats::transparentWholeMeshes
    if (pc.dispatchArgs != FGB_NONE) {  // the cluster form: one "Transparent Raster" workgroup per draw
      const uint width = 32768u;
      fgbUints[pc.dispatchArgs].values[0] = min(draws, width);
      fgbUints[pc.dispatchArgs].values[1] = (draws + width - 1u) / width;
      fgbUints[pc.dispatchArgs].values[2] = 1u;
    }
  }
}
