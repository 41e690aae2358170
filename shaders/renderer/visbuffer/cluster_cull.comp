#version 460
// "Cluster Cull": one invocation per cluster of every opaque or alpha-masked instance. The
// instance's world AABB and then the cluster's bounding sphere are tested against the six frustum
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

// The frame's frustum planes (render space), from its FrameConstants.
vec4 plane(int i) { return fgbFrames[pc.frame].frame.frustumPlanes[i]; }

bool boxInside(vec3 boxMin, vec3 boxMax) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = plane(i);
    vec3 positive = mix(boxMin, boxMax, greaterThanEqual(p.xyz, vec3(0.0)));
    if (dot(p.xyz, positive) + p.w < 0.0) return false;
  }
  return true;
}

bool sphereInside(vec3 center, float radius) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = plane(i);
    if (dot(p.xyz, center) + p.w < -radius) return false;
  }
  return true;
}

// render.occlusion and a pyramid from last frame (none on the first frame: the frame's flag).
bool hizUsable() {
  return (pc.drawCount & kCullOcclusion) != 0u && (fgbFrames[pc.frame].frame.step.y & kFrameHizValid) != 0u;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= (pc.drawCount & kCullDrawCountMask)) return;
  ClusterDraw draw = visDraws[pc.draws].draws[id];
  Instance inst = fgbInstances[pc.instances].instances[draw.instance];
  if (!boxInside(inst.boundsMin.xyz, inst.boundsMax.xyz)) return;
  ClusterData cluster = visClusters[pc.clusters].clusters[draw.cluster];
  vec3 center = (inst.model * vec4(cluster.sphere.xyz, 1.0)).xyz;
  float radius = cluster.sphere.w * maxScale(inst.model);
  if (!sphereInside(center, radius)) return;
  if ((draw.flags & (kClusterSingleSided | kClusterConeUsable)) == (kClusterSingleSided | kClusterConeUsable) &&
      cluster.cone.w < 1.0) {
    // Front is defined in object space (glTF), so the axis transforms as a normal.
    vec3 axis = normalize(mat3(inst.normalMatrix) * cluster.cone.xyz);
    vec3 fromEye = center - fgbFrames[pc.frame].frame.cameraPosition.xyz;
    if (dot(fromEye, axis) >= cluster.cone.w * length(fromEye) + radius) return;
  }
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
}
