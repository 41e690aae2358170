#version 460
// "Mesh Render" fragment stage: the shared surface shading (include/surface_shading.glsl) with
// implicit-derivative texture sampling; alpha-masked materials discard below their cutoff. On the
// visibility-buffer path the transparent pass has no depth attachment and its variant of this shader
// (FGB_OPAQUE_DEPTH_TEST, shaders/CMakeLists.txt) tests the opaque depth first
// (include/opaque_depth.glsl), so hidden fragments cost one load.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/forward_push.glsl"
#include "include/surface_shading.glsl"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) flat in uint inMaterial;
#ifdef FGB_DEBUG_VIEWS
// "Meshlet Render" with debug.view=lod|clusters (the mesh shader's debug variant writes it).
#include "include/debug_views.glsl"
layout(location = 5) flat in uvec3 inDebugCluster;
#endif

layout(location = 0) out vec4 outColor;

vec4 sampleSurfaceTexture(int textureIndex, vec2 uv) {
  return sampleMaterialTexture(textureIndex, pc.materialSampler, uv);
}

void main() {
#ifdef FGB_OPAQUE_DEPTH_TEST
  if (!passesOpaqueDepth(pc.opaqueDepth, gl_FragCoord)) discard;
#endif
  FrameConstants frame = fgbFrames[pc.frame].frame;
  Material m = fgbMaterials[pc.materials].materials[inMaterial];
  vec2 uv = safeUv(inUv);
  vec4 base = surfaceBaseColor(m, uv);
  if (m.alphaMode == 1u && base.a < m.alphaCutoff) discard;
  vec3 geometricNormal = cross(dFdx(inWorldPosition), dFdy(inWorldPosition));
  SurfacePoint p = SurfacePoint(inWorldPosition, inNormal, inTangent, uv, gl_FrontFacing, gl_FragCoord.xy,
                                geometricNormal);
  outColor = shadeSurface(frame, m, base, p, LightLists(pc.lights, pc.clusterCounts, pc.clusterIndices));
#ifdef FGB_DEBUG_VIEWS
  if (frame.counts.w >= kDebugViewLod) {
    outColor.rgb = debugViewColor(frame.counts.w, inDebugCluster.x, inDebugCluster.y, inDebugCluster.z, inNormal,
                                  frame.cameraPosition.xyz - inWorldPosition, preExposure(frame));
  }
#endif
  if ((pc.flags & kForwardInjectBias) != 0u) outColor.rgb += kInjectedBias;  // debug.inject_bias
  if ((pc.flags & kForwardInjectNan) != 0u && ivec2(gl_FragCoord.xy) == ivec2(frame.viewport.xy) / 2) {
    outColor.rgb = vec3(uintBitsToFloat(0x7fc00000u));  // debug.inject_nan: a NaN at the centre pixel
  }
}
