// HiZ occlusion (render.occlusion=1; included by cluster_cull.comp, cluster_cull_late.comp,
// hiz_build.comp and the meshlet path's meshlet.task). The HiZ pyramid is a storage buffer of depth keys (depthKey in clusters.glsl:
// larger = nearer, 0 = no triangle): level k >= 1 has ceil(W / 2^k) x ceil(H / 2^k) texels, row
// major, levels one after another from level 1; texel (i, j) of level k holds the smallest key,
// i.e. the farthest depth, of the viewport's pixels [i * 2^k, (i + 1) * 2^k) x [j * 2^k, ...)
// (clamped to the viewport), so a sphere whose nearest depth is farther than a texel's key is
// hidden at every pixel the texel covers. (Level 0, the pixels themselves, is not stored.)
#ifndef FGB_RENDERER_HIZ_OCCLUSION_GLSL
#define FGB_RENDERER_HIZ_OCCLUSION_GLSL

#include "renderer/shared/hiz.h"

// The shared layout (renderer/shared/hiz.h) per viewport.
uvec2 hizLevelSize(uvec2 viewport, uint level) {
  return uvec2(hizLevelSide(viewport.x, level), hizLevelSide(viewport.y, level));
}
uint hizLevelOffset(uvec2 viewport, uint level) { return hizLevelOffset(viewport.x, viewport.y, level); }
uint hizLevels(uvec2 viewport) { return hizLevels(viewport.x, viewport.y); }

#ifndef FGB_HIZ_BUILD_ONLY
// Whether a world-space sphere is certainly hidden behind the depths the pyramid `hiz` holds.
// Conservative: a sphere crossing the near plane or behind the eye is visible; the sphere is
// enlarged, its screen rectangle grown by a pixel, and its depth key must be below the texels'
// farthest by a margin, so rounding in the raster's depths can never hide a pixel it would win.
// `frame`: the frame constants' storage-buffer index (only the fields used are loaded).
bool hizOccluded(uint hiz, uint frame, vec3 center, float radius, bool reversedZ) {
  mat4 view = fgbFrames[frame].frame.view;
  mat4 proj = fgbFrames[frame].frame.proj;
  vec2 viewportSize = fgbFrames[frame].frame.viewport.xy;
  vec3 viewCenter = (view * vec4(center, 1.0)).xyz;
  float r = radius * 1.001 + 1e-4 * length(viewCenter);
  float nearestZ = viewCenter.z + r;  // the view looks down -z
  if (-nearestZ <= fgbFrames[frame].frame.depthRange.x) return false;  // crosses the near plane, or behind the eye
  // The screen rectangle of the sphere's view-space bounding box (its 8 corners are in front of
  // the eye, so the projection of the box, which holds the sphere's, is their hull).
  vec2 ndcMin = vec2(1e30), ndcMax = vec2(-1e30);
  for (uint i = 0u; i < 8u; ++i) {
    vec3 corner = viewCenter + r * vec3((i & 1u) != 0u ? 1.0 : -1.0, (i & 2u) != 0u ? 1.0 : -1.0, (i & 4u) != 0u ? 1.0 : -1.0);
    vec4 clip = proj * vec4(corner, 1.0);
    vec2 ndc = clip.xy / clip.w;
    ndcMin = min(ndcMin, ndc);
    ndcMax = max(ndcMax, ndc);
  }
  vec4 nearestClip = proj * vec4(viewCenter.xy, nearestZ, 1.0);
  uint sphereKey = depthKey(nearestClip.z / nearestClip.w, reversedZ);

  uvec2 viewport = uvec2(viewportSize);
  vec2 lo = clamp(floor((ndcMin * 0.5 + 0.5) * viewportSize) - 1.0, vec2(0.0), viewportSize - 1.0);
  vec2 hi = clamp(floor((ndcMax * 0.5 + 0.5) * viewportSize) + 1.0, vec2(0.0), viewportSize - 1.0);
  uvec2 p0 = uvec2(lo), p1 = uvec2(hi);
  // The finest level at which the rectangle spans at most 2 x 2 texels: a span s < 2^k does at
  // level k, one of s < 2^(k+1) may at level k, so the search starts at findMSB(s).
  uint levels = hizLevels(viewport);
  uvec2 span = p1 - p0;
  uint level = uint(clamp(findMSB(max(span.x, span.y)), 1, int(levels)));
  while (level < levels && any(greaterThan((p1 >> level) - (p0 >> level), uvec2(1u)))) ++level;
  uvec2 size = hizLevelSize(viewport, level);
  uint base = hizLevelOffset(viewport, level);
  uvec2 t0 = p0 >> level, t1 = min(p1 >> level, size - 1u);
  uint farthest = 0xffffffffu;
  for (uint y = t0.y; y <= t1.y; ++y)
    for (uint x = t0.x; x <= t1.x; ++x) farthest = min(farthest, fgbUintsRead[hiz].values[base + y * size.x + x]);
  // Keys are float bits: 64 units is 64 ulps of depth, beyond the raster's interpolation error.
  return farthest > 64u && sphereKey < farthest - 64u;
}
#endif

#endif
