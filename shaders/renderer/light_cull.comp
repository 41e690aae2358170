#version 460
// "Clustered Light Cull" (thesis): one workgroup per cluster; each invocation tests every 64th
// point light (sphere vs the cluster's view-space AABB). Indices are gathered in shared memory and
// copied to the cluster's fixed-capacity slot of the global list, so no global counter exists
// and nothing depends on ordering between workgroups. Overflowing lights are dropped (guard).
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"

#define GROUP_SIZE 64
#define MAX_LIGHTS_PER_CLUSTER 1024
layout(local_size_x = GROUP_SIZE) in;

layout(push_constant) uniform Push {
  uint frame;
  uint bounds;
  uint lights;
  uint counts;   // per cluster: lights found (may exceed the capacity: overflow is visible)
  uint indices;  // cluster c's lights at [c * capacity, c * capacity + min(count, capacity))
} pc;

shared uint sharedCount;
shared uint sharedIndices[MAX_LIGHTS_PER_CLUSTER];

bool sphereIntersectsBox(vec3 center, float radius, vec3 boxMin, vec3 boxMax) {
  vec3 closest = clamp(center, boxMin, boxMax);
  vec3 d = center - closest;
  return dot(d, d) <= radius * radius;
}

void main() {
  uint cluster = gl_WorkGroupID.x;
  FrameConstants frame = fgbFrames[pc.frame].frame;
  uint capacity = min(frame.counts.z, uint(MAX_LIGHTS_PER_CLUSTER));
  if (gl_LocalInvocationIndex == 0u) sharedCount = 0u;
  barrier();  // workgroup-local: orders the reset before every append of this workgroup

  vec3 boxMin = fgbVec4sRead[pc.bounds].values[2u * cluster].xyz;
  vec3 boxMax = fgbVec4sRead[pc.bounds].values[2u * cluster + 1u].xyz;
  for (uint i = gl_LocalInvocationIndex; i < frame.counts.x; i += GROUP_SIZE) {
    PointLight light = fgbLights[pc.lights].lights[i];
    vec3 center = (frame.view * vec4(light.positionRadius.xyz, 1.0)).xyz;
    if (!sphereIntersectsBox(center, light.positionRadius.w, boxMin, boxMax)) continue;
    uint slot = atomicAdd(sharedCount, 1u);
    if (slot < capacity) sharedIndices[slot] = i;
  }
  barrier();

  uint found = sharedCount;
  uint stored = min(found, capacity);
  for (uint i = gl_LocalInvocationIndex; i < stored; i += GROUP_SIZE)
    fgbUints[pc.indices].values[cluster * capacity + i] = sharedIndices[i];
  if (gl_LocalInvocationIndex == 0u) fgbUints[pc.counts].values[cluster] = found;
}
