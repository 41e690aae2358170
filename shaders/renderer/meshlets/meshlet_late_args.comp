#version 460
// render.occlusion, after "HiZ Build": the arguments of "Meshlet Render (late)", one task draw
// whose workgroups take the candidates phase 1 held back FGB_MESHLET_TASK_GROUP_SIZE at a time
// (no draw when there are none).
#extension GL_GOOGLE_include_directive : require
#include "../include/common.glsl"
#include "renderer/shared/meshlets.h"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { MeshletLateArgsPush pc; };

void main() {
  uint candidates = fgbUintsRead[pc.candidates].values[0];
  uint at = FGB_MESHLET_COMMANDS_OFFSET / 4;
  fgbUints[pc.commands].values[0] = candidates > 0u ? 1u : 0u;
  fgbUints[pc.commands].values[at] = (candidates + FGB_MESHLET_TASK_GROUP_SIZE - 1u) / FGB_MESHLET_TASK_GROUP_SIZE;
  fgbUints[pc.commands].values[at + 1u] = 1u;
  fgbUints[pc.commands].values[at + 2u] = 1u;
  fgbUints[pc.commands].values[at + 3u] = 0u;
}
