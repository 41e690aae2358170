#version 460
// "Transparent Shade" (render.transparent=compute): one workgroup per tile "Transparent Raster"
// listed (a tile some fragment landed in; indirect, TransparentCounters::shadeGroups), one
// invocation per pixel of it, so tiles without transparent fragments cost nothing. A pixel whose
// first K-buffer slot is empty has no transparent fragment and leaves at once (one 8-byte load). The
// others shade each kept fragment at the pixel centre as "Material Shade" shades an opaque one
// (shadeTrianglePixel: the forward path's surface_shading.glsl, pre-exposed) and blend them far to
// near over the HDR image with the raster pass's blend state (rhi BlendMode::Alpha: colour
// src.a * src + (1 - src.a) * dst, alpha src.a + (1 - src.a) * dst.a), in float, rounding to R16F
// once where the raster pass rounds after each fragment. It empties the slots it read: the
// K-buffer persists from frame to frame, empty between them, so no pass fills all of it; likewise
// the tile's flag (the raster lists each tile once a frame).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "../include/visbuffer_material.glsl"
#include "../include/transparent_compute.glsl"

layout(local_size_x = FGB_TRANSPARENT_SHADE_GROUP_SIZE, local_size_y = FGB_TRANSPARENT_SHADE_GROUP_SIZE) in;

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) uniform image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

void main() {
  loadFrameGlobals();
  uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (group >= fgbUintsRead[pc.tileJobs].values[0]) return;  // the last row's spill past the count
  uint tile = fgbUintsRead[pc.tileJobs].values[1u + group];
  if (gl_LocalInvocationIndex == 0u) visWords[pc.words].words[tileFlagIndex(tile)] = kEmpty;
  uvec2 pixel = uvec2(tile % tilesAcross(), tile / tilesAcross()) * FGB_TRANSPARENT_SHADE_GROUP_SIZE + gl_LocalInvocationID.xy;
  uvec2 size = uvec2(viewportSize());
  if (any(greaterThanEqual(pixel, size))) return;
  uint index = pixel.y * size.x + pixel.x;
  if (visWords[pc.words].words[index] == kEmpty) return;
  uint ids[TRANSPARENT_K];
  int kept = 0;
  for (uint i = 0u; i < TRANSPARENT_K; ++i) {
    uint64_t word = visWords[pc.words].words[kSlotIndex(i, index)];
    if (word == kEmpty) break;  // the slots fill from the nearest: the rest are empty too
    ids[kept++] = uint(word);
    visWords[pc.words].words[kSlotIndex(i, index)] = kEmpty;  // empty for the next frame's raster
  }
  vec4 dst = imageLoad(fgbImagesRgba16f[pc.hdr], ivec2(pixel));
  for (int i = kept - 1; i >= 0; --i) {
    SurfacePoint p;
    vec4 src = shadeTrianglePixel(transparentTriangle(ids[i]), pixel, p);
    dst = vec4(src.rgb * src.a + dst.rgb * (1.0 - src.a), src.a + dst.a * (1.0 - src.a));
  }
  imageStore(fgbImagesRgba16f[pc.hdr], ivec2(pixel), dst);
}
