#version 460
// "Mesh Frustum Cull", second dispatch (after a barrier in the same node): copies the draw groups
// that received visible instances into one packed command list per batch (opaque, alpha-masked,
// transparent) and writes each batch's draw count, so "Mesh Render" issues
// vkCmdDrawIndexedIndirectCount over visible groups only. The packing keeps group order (an
// exclusive scan, not atomics): transparent groups stay sorted back to front, and the result is
// the same on every run. One workgroup per batch.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "renderer/shared/meshes.h"

#define WIDTH FGB_MESH_COMPACT_GROUP_SIZE
layout(local_size_x = WIDTH) in;

layout(push_constant) uniform Push { MeshCompactPush pc; };

shared uint inclusive[WIDTH];

// Inclusive prefix sum of `value` over the workgroup (Hillis-Steele; WIDTH is small).
uint workgroupInclusiveSum(uint value) {
  const uint lane = gl_LocalInvocationID.x;
  inclusive[lane] = value;
  barrier();
  for (uint offset = 1u; offset < WIDTH; offset <<= 1u) {
    uint add = lane >= offset ? inclusive[lane - offset] : 0u;
    barrier();
    inclusive[lane] += add;
    barrier();
  }
  return inclusive[lane];
}

void main() {
  const uvec4 batch = pc.batches[gl_WorkGroupID.x];
  const uint lane = gl_LocalInvocationID.x;
  uint packed = 0u;
  for (uint base = 0u; base < batch.y; base += WIDTH) {
    const uint group = batch.x + base + lane;
    const bool drawn = base + lane < batch.y && fgbCommands[pc.commands].commands[group].instanceCount > 0u;
    const uint position = workgroupInclusiveSum(drawn ? 1u : 0u);
    if (drawn) {
      fgbCommands[pc.drawList].commands[batch.x + packed + position - 1u] = fgbCommands[pc.commands].commands[group];
    }
    packed += inclusive[WIDTH - 1u];
    barrier();  // everyone read the total before the next chunk overwrites it
  }
  if (lane == 0u) {
    fgbUints[pc.drawCounts].values[gl_WorkGroupID.x] = packed;
    atomicAdd(fgbUints[pc.stats].values[2], packed);
  }
}
