#version 460
// "Cluster Cull": one invocation per cluster of every opaque or alpha-masked instance. The
// instance's world AABB and then the cluster's bounding sphere are tested against the six frustum
// planes; clusters of single-sided materials are also dropped when their normal cone faces away
// from the camera (meshoptimizer's cone test). Survivors are appended to the visible-cluster list
// ("Triangle Filter" runs one workgroup per entry). Counters were zeroed by "Visibility Clear".
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform Push {
  vec4 planes[6];  // inside: dot(n, p) + d >= 0
  uint frame;
  uint instances;
  uint draws;
  uint clusters;
  uint counters;
  uint visible;    // visible-cluster list: ClusterDraw indices
  uint drawCount;
} pc;

bool boxInside(vec3 boxMin, vec3 boxMax) {
  for (int i = 0; i < 6; ++i) {
    vec3 n = pc.planes[i].xyz;
    vec3 positive = mix(boxMin, boxMax, greaterThanEqual(n, vec3(0.0)));
    if (dot(n, positive) + pc.planes[i].w < 0.0) return false;
  }
  return true;
}

bool sphereInside(vec3 center, float radius) {
  for (int i = 0; i < 6; ++i)
    if (dot(pc.planes[i].xyz, center) + pc.planes[i].w < -radius) return false;
  return true;
}

float maxScale(mat4 model) {
  return sqrt(max(dot(model[0].xyz, model[0].xyz), max(dot(model[1].xyz, model[1].xyz), dot(model[2].xyz, model[2].xyz))));
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= pc.drawCount) return;
  ClusterDraw draw = visDraws[pc.draws].draws[id];
  Instance inst = fgbInstances[pc.instances].instances[draw.instance];
  if (!boxInside(inst.boundsMin.xyz, inst.boundsMax.xyz)) return;
  ClusterData cluster = visClusters[pc.clusters].clusters[draw.cluster];
  vec3 center = (inst.model * vec4(cluster.sphere.xyz, 1.0)).xyz;
  float radius = cluster.sphere.w * maxScale(inst.model);
  if (!sphereInside(center, radius)) return;
  if ((draw.flags & (kDrawSingleSided | kDrawConeUsable)) == (kDrawSingleSided | kDrawConeUsable) &&
      cluster.cone.w < 1.0) {
    // Front is defined in object space (glTF), so the axis transforms as a normal.
    vec3 axis = normalize(mat3(inst.normalMatrix) * cluster.cone.xyz);
    vec3 fromEye = center - fgbFrames[pc.frame].frame.cameraPosition.xyz;
    if (dot(fromEye, axis) >= cluster.cone.w * length(fromEye) + radius) return;
  }
  uint slot = atomicAdd(visCounters[pc.counters].c.visibleClusters, 1u);
  fgbUints[pc.visible].values[slot] = id;
}
