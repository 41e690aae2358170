#version 460
// "Mesh Frustum Cull": one invocation per instance tests its world AABB against the six frustum
// planes (p-vertex test, Assarsson-Moeller) and appends visible instances to their draw group's
// indirect command. The commands' instance counts and the stats were reset by an earlier node.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "renderer/shared/meshes.h"

layout(local_size_x = FGB_MESH_CULL_GROUP_SIZE) in;

layout(push_constant) uniform Push { MeshCullPush pc; };

bool insideFrustum(vec3 boxMin, vec3 boxMax) {
  if (boxMin.x > boxMax.x) return false;  // empty box
  for (int i = 0; i < 6; ++i) {
    vec4 plane = fgbFrames[pc.frame].frame.frustumPlanes[i];
    vec3 n = plane.xyz;
    vec3 positive = mix(boxMin, boxMax, greaterThanEqual(n, vec3(0.0)));
    if (dot(n, positive) + plane.w < 0.0) return false;
  }
  return true;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= pc.instanceCount) return;
  Instance inst = fgbInstances[pc.instances].instances[id];
  if (!insideFrustum(inst.boundsMin.xyz, inst.boundsMax.xyz)) return;
  uint group = inst.drawGroup;
  uint slot = atomicAdd(fgbCommands[pc.commands].commands[group].instanceCount, 1u);
  fgbUints[pc.visible].values[fgbCommands[pc.commands].commands[group].firstInstance + slot] = id;
  atomicAdd(fgbUints[pc.stats].values[0], 1u);
  atomicAdd(fgbUints[pc.stats].values[1], inst.triangles);
  if (group >= pc.firstTransparentGroup) atomicAdd(fgbUints[pc.stats].values[3], inst.triangles);
}
