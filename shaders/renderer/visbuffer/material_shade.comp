#version 460
// "Material Shade": one invocation per pixel. It decodes the pixel's visibility word, rebuilds
// the triangle from its id (visible cluster -> instance, cluster -> three vertices) and shades it
// at the pixel centre (shadeTrianglePixel in visbuffer_material.glsl: perspective-correct
// barycentrics with analytic derivatives, the forward path's surface_shading.glsl), writing the
// HDR target, and empties the pixel's word (the buffer stays cleared between frames). It also
// writes the pixel's depth (the far value where nothing was drawn), which the transparent and
// particle passes test their fragments against (include/opaque_depth.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "../include/visbuffer_material.glsl"

layout(local_size_x = FGB_VIS_SHADE_GROUP_SIZE, local_size_y = FGB_VIS_SHADE_GROUP_SIZE) in;

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) uniform writeonly image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

#ifdef FGB_DEBUG_VIEWS
#include "../include/debug_views.glsl"

vec3 debugViewColor(FrameConstants frame, uint drawIndex, SurfacePoint p) {
  ClusterDraw draw = visDraws[pc.draws].draws[drawIndex];
  uint lodLevel = visClusters[pc.clusters].clusters[draw.cluster].lodLevel;
  return debugViewColor(frame.counts.w, lodLevel, draw.cluster, draw.instance, p.normal,
                        frame.cameraPosition.xyz - p.worldPosition, preExposure(frame));
}
#endif

// The first workgroup copies both phases' culling counters to the host's statistics, a word per
// invocation (pc.args: the phases' snapshots, 16 bits each; pc.counters: the host-visible copy).
void copyCountersToHost() {
  uint word = gl_LocalInvocationIndex;
  if (word >= 2u * kVisCounterWords) return;
  uint source = word < kVisCounterWords ? (pc.args & 0xffffu) : (pc.args >> 16);
  fgbUints[pc.counters].values[word] =
      source == kVisNoPhase ? 0u : fgbUintsRead[source].values[word % kVisCounterWords];
}

void main() {
  if (gl_WorkGroupID.xy == uvec2(0u)) copyCountersToHost();
  loadFrameGlobals();
  uvec2 pixel = gl_GlobalInvocationID.xy;
  uvec2 size = uvec2(viewportSize());
  if (any(greaterThanEqual(pixel, size))) return;
  uint index = pixel.y * size.x + pixel.x;
  uint64_t word = visWordTake(pc.words, ivec2(pixel), size.x);
  if (word == 0ul) {
    visFloats[pc.depthOut].values[index] = reversedZ() ? 0.0 : 1.0;
    imageStore(fgbImagesRgba16f[pc.hdr], ivec2(pixel), pc.background);
    return;
  }
  visFloats[pc.depthOut].values[index] = depthFromKey(uint(word >> 32), reversedZ());
  uint id = uint(word);
  uint drawIndex = id >> kClusterTriangleBits;
  VisTriangle tri = visTriangle(drawIndex, id & ((1u << kClusterTriangleBits) - 1u), pc.draws, pc.clusters, pc.indices);
  SurfacePoint p;
  vec4 color = shadeTrianglePixel(tri, pixel, p);
#ifdef FGB_DEBUG_VIEWS
  FrameConstants frame = fgbFrames[pc.frame].frame;
  if (frame.counts.w >= kDebugViewLod) color.rgb = debugViewColor(frame, drawIndex, p);
#endif
  if ((pc.flags & kFlagInjectBias) != 0u) color.rgb += kInjectedBias;  // debug.inject_bias
  imageStore(fgbImagesRgba16f[pc.hdr], ivec2(pixel), vec4(color.rgb, 1.0));  // alpha > 0: metered geometry
}
