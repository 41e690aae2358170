// Push constants of the forward passes (mirrors ForwardPush in meshes/mesh_feature.cpp).
#ifndef FGB_RENDERER_FORWARD_PUSH_GLSL
#define FGB_RENDERER_FORWARD_PUSH_GLSL
#include "opaque_depth.glsl"
layout(push_constant) uniform Push {
  uint frame;
  uint instances;
  uint visible;
  uint materials;
  uint lights;
  uint clusterCounts;   // FGB_NONE: no clustered lighting (loop over all lights)
  uint clusterIndices;
  uint materialSampler;
  uint flags;           // bit 0: alpha-masked pass, bit 1: transparent pass, bit 2: inject a NaN
  OpaqueDepthTest opaqueDepth;  // visibility buffer, transparent pass: the depth test (forward.frag)
} pc;
#endif
