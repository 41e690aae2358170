#version 460
// "Cluster Cull": one invocation per cluster, of every LOD level, of every opaque or alpha-masked
// instance. The tests are include/clusters.glsl's, which the meshlet path's task shader applies
// too. First the LOD cut (lodInCut): the cluster is kept when its own error projects to at
// most the threshold and its parent group's error to more, so of each mesh one consistent cut is
// drawn (scene::Cluster). Then the instance's world AABB and the cluster's bounding sphere are
// tested against the six frustum
// planes; clusters of single-sided materials are also dropped when their normal cone faces away
// from the camera (meshoptimizer's cone test). Survivors are appended to the visible-cluster list
// ("Triangle Filter" runs one workgroup per entry). Counters were zeroed by "Visibility Clear".
// With render.occlusion=1 (phase 1 of two-phase occlusion culling) survivors whose sphere is
// hidden behind last frame's HiZ pyramid go to the occlusion candidates instead, which
// "Cluster Cull (late)" re-tests against this frame's (cluster_cull_late.comp).
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"
#include "hiz_occlusion.glsl"

layout(local_size_x = FGB_VIS_CULL_GROUP_SIZE) in;

layout(push_constant) uniform Push { ClusterCullPush pc; };

// render.occlusion and a pyramid from last frame (none on the first frame: the frame's flag).
bool hizUsable() {
  return (pc.drawCount & kCullOcclusion) != 0u && (fgbFrames[pc.frame].frame.step.y & kFrameHizValid) != 0u;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= (pc.drawCount & kCullDrawCountMask)) return;
  uint frame = pc.frame;
  ClusterDraw draw = visDraws[pc.draws].draws[id];
  Instance inst = fgbInstances[pc.instances].instances[draw.instance];
  if (!boxInside(frame, inst.boundsMin.xyz, inst.boundsMax.xyz)) return;
  ClusterData cluster = visClusters[pc.clusters].clusters[draw.cluster];
  float scale = maxScale(inst.model);
  if (!lodInCut(cluster, inst.model, scale, frame, pc.lodThreshold)) return;
  vec3 center = (inst.model * vec4(cluster.sphere.xyz, 1.0)).xyz;
  float radius = cluster.sphere.w * scale;
  if (!sphereInside(frame, center, radius)) return;
  if (clusterConeCulled(cluster, draw.flags, inst, center, radius, frame)) return;
  bool holdBack = (pc.drawCount & kCullHoldBackOdd) != 0u && (id & 1u) != 0u;
  if (holdBack || (hizUsable() &&
                   hizOccluded(pc.occlusion & 0xffffu, pc.frame, center, radius,
                               (pc.drawCount & kCullReversedZ) != 0u))) {
    uint candidate = atomicAdd(visCounters[pc.counters].c.occluded, 1u);
    fgbUints[pc.occlusion >> 16].values[candidate] = id;
    return;
  }
  uint slot = atomicAdd(visCounters[pc.counters].c.visibleClusters, 1u);
  fgbUints[pc.visible].values[slot] = id;
  atomicAdd(visCounters[pc.counters].c.lodClusters[min(cluster.lodLevel, FGB_VIS_LOD_STAT_LEVELS - 1)], 1u);
}
