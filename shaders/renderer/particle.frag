#version 460
// Soft round particle, alpha blended over the opaque scene. On the visibility-buffer path there is
// no depth attachment: this shader's FGB_OPAQUE_DEPTH_TEST variant tests the opaque depth first
// (include/opaque_depth.glsl).
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/opaque_depth.glsl"
#include "renderer/shared/particles.h"

layout(push_constant) uniform Push { ParticleRenderPush pc; };

layout(location = 0) in vec4 inColor;
layout(location = 1) in vec2 inCorner;
layout(location = 0) out vec4 outColor;

void main() {
#ifdef FGB_OPAQUE_DEPTH_TEST
  if (!passesOpaqueDepth(pc.opaqueDepth, gl_FragCoord)) discard;
#endif
  float falloff = clamp(1.0 - dot(inCorner, inCorner), 0.0, 1.0);
  outColor = vec4(inColor.rgb, inColor.a * falloff * falloff);
}
