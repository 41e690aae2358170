// Shared by the meshlet path's task and mesh shaders: the push block (MeshletPush,
// renderer/shared/meshlets.h) and the payload the task shader hands to its mesh workgroups.
#ifndef FGB_RENDERER_MESHLET_GLSL
#define FGB_RENDERER_MESHLET_GLSL

#extension GL_EXT_mesh_shader : require
#include "../include/clusters.glsl"
#include "renderer/shared/meshlets.h"

layout(push_constant) uniform Push { MeshletPush pc; };

// The cluster draws (ClusterDraw indices) that survived the task shader, in lane order: mesh
// workgroup i draws draws[i].
struct MeshletPayload {
  uint draws[FGB_MESHLET_TASK_GROUP_SIZE];
};
taskPayloadSharedEXT MeshletPayload payload;

#endif
