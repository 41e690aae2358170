// Push constants of the forward passes: ForwardPush (renderer/shared/meshes.h).
#ifndef FGB_RENDERER_FORWARD_PUSH_GLSL
#define FGB_RENDERER_FORWARD_PUSH_GLSL
#include "opaque_depth.glsl"
#include "renderer/shared/meshes.h"
layout(push_constant) uniform Push { ForwardPush pc; };
#endif
