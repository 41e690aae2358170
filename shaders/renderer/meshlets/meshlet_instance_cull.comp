#version 460
// "Meshlet Instance Cull": one invocation per GPU instance. An opaque or alpha-masked instance
// (one with cluster draws) whose render-space box meets the frustum gets one task draw: its
// cluster draws in workgroups of FGB_MESHLET_TASK_GROUP_SIZE, which the task shader culls one by
// one. The draw count (the header's first word) and the statistics were zeroed by "Meshlet
// Reset"; the order of the draws does not matter (the opaque scene is depth-tested).
#extension GL_GOOGLE_include_directive : require
#include "../include/clusters.glsl"
#include "renderer/shared/meshlets.h"

layout(local_size_x = FGB_MESHLET_CULL_GROUP_SIZE) in;

layout(push_constant) uniform Push { MeshletCullPush pc; };

const uint kCommandWords = 4u;  // MeshletTaskCommand
const uint kHeaderWords = FGB_MESHLET_COMMANDS_OFFSET / 4;

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= pc.instanceCount) return;
  uint draws = fgbUintsRead[pc.ranges].values[2u * slot + 1u];
  if (draws == 0u) return;  // transparent: "Mesh Render Transparent" draws it
  Instance inst = fgbInstances[pc.instances].instances[slot];
  if (!boxInside(pc.frame, inst.boundsMin.xyz, inst.boundsMax.xyz)) return;
  uint command = atomicAdd(fgbUints[pc.commands].values[0], 1u);
  uint at = kHeaderWords + kCommandWords * command;
  fgbUints[pc.commands].values[at] = (draws + FGB_MESHLET_TASK_GROUP_SIZE - 1u) / FGB_MESHLET_TASK_GROUP_SIZE;
  fgbUints[pc.commands].values[at + 1u] = 1u;
  fgbUints[pc.commands].values[at + 2u] = 1u;
  fgbUints[pc.commands].values[at + 3u] = slot;
  atomicAdd(fgbUints[pc.stats].values[0], 1u);  // MeshletStats::instancesVisible
}
