#version 460
// "Mesh Render" vertex stage: instance data is fetched through the visible-instance list the cull
// pass wrote; gl_InstanceIndex includes the command's firstInstance (the group's list offset). The
// transparent instances' cluster draws ("Transparent Cluster Cull") name the instance itself
// (kForwardInstanceIsSlot).
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/forward_push.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv;
layout(location = 4) flat out uint outMaterial;
// The depth prepass and Mesh Render must produce bit-identical depth (GreaterOrEqual test, reversed-Z).
invariant gl_Position;

void main() {
  uint instanceId = (pc.flags & kForwardInstanceIsSlot) != 0u ? uint(gl_InstanceIndex)
                                                              : fgbUintsRead[pc.visible].values[gl_InstanceIndex];
  Instance inst = fgbInstances[pc.instances].instances[instanceId];
  vec4 world = inst.model * vec4(inPosition, 1.0);
  outWorldPosition = world.xyz;
  outNormal = mat3(inst.normalMatrix) * inNormal;
  outTangent = vec4(mat3(inst.model) * inTangent.xyz, inTangent.w);
  outUv = inUv;
  outMaterial = inst.material;
  gl_Position = fgbFrames[pc.frame].frame.viewProj * world;
}
