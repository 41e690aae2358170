#version 460
// "Cluster Cull (late)" (render.occlusion=1, phase 2 of two-phase occlusion culling): one
// invocation per occlusion candidate of "Cluster Cull" (clusters inside the frustum and facing
// the camera, in the LOD cut, but hidden behind last frame's HiZ). Each is tested again against the HiZ pyramid
// of this frame's phase-1 depths ("HiZ Build"); those not hidden are appended to the
// visible-cluster list after phase 1's clusters, counted in the late counters (which "Triangle
// Filter (late)" and "Visibility Raster (late)" go on with).
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"
#include "hiz_occlusion.glsl"

layout(local_size_x = FGB_VIS_CULL_GROUP_SIZE) in;

layout(push_constant) uniform Push { LateCullPush pc; };

void main() {
  uint id = gl_GlobalInvocationID.x;
  VisCounters early = visCountersRead[pc.earlyArgs].c;
  if (id == 0u) visCounters[pc.counters].c.firstCluster = early.visibleClusters;
  if (id >= early.occluded) return;
  uint drawIndex = fgbUintsRead[pc.candidates].values[id];
  ClusterDraw draw = visDraws[pc.draws].draws[drawIndex];
  Instance inst = fgbInstances[pc.instances].instances[draw.instance];
  ClusterData cluster = visClusters[pc.clusters].clusters[draw.cluster];
  vec3 center = (inst.model * vec4(cluster.sphere.xyz, 1.0)).xyz;
  float radius = cluster.sphere.w * maxScale(inst.model);
  if (hizOccluded(pc.hiz, pc.frame, center, radius, pc.reversedZ != 0u)) return;
  uint slot = atomicAdd(visCounters[pc.counters].c.visibleClusters, 1u);
  fgbUints[pc.visible].values[early.visibleClusters + slot] = drawIndex;
  atomicAdd(visCounters[pc.counters].c.lodClusters[min(cluster.lodLevel, FGB_VIS_LOD_STAT_LEVELS - 1)], 1u);
}
