// debug.view=lod|clusters: the colours both paths that draw clusters give them, "Material Shade"
// (visibility buffer) and "Meshlet Render" (forward.frag's debug variant). Only the "debug" shader
// variants include this (shaders/CMakeLists.txt), so the measured shaders carry no such branch.
#ifndef FGB_DEBUG_VIEWS_GLSL
#define FGB_DEBUG_VIEWS_GLSL

#include "renderer/shared/debug.h"

// lod: the cluster's LOD level (0 blue, then cyan, green, yellow, orange, red, magenta, white from
// level 7 on); clusters: a colour per cluster of each instance. Lit by the angle between `normal`
// and `toEye` so the shapes stay readable, and scaled by `exposure` (pre-exposed like shading).
vec3 debugViewColor(uint view, uint lodLevel, uint cluster, uint instance, vec3 normal, vec3 toEye, float exposure) {
  vec3 color;
  if (view == kDebugViewLod) {
    const vec3 levels[8] = vec3[8](vec3(0.1, 0.2, 1.0), vec3(0.0, 0.9, 1.0), vec3(0.1, 1.0, 0.1), vec3(1.0, 1.0, 0.0),
                                   vec3(1.0, 0.5, 0.0), vec3(1.0, 0.05, 0.05), vec3(1.0, 0.1, 1.0), vec3(1.0));
    color = levels[min(lodLevel, 7u)];
  } else {
    uint h = (cluster * 0x9e3779b1u) ^ (instance * 0x85ebca6bu);
    h = (h ^ (h >> 15)) * 0x2c1b3c6du;
    color = vec3(uvec3(h, h >> 8, h >> 16) & 0xffu) / 255.0 * 0.8 + 0.2;
  }
  float facing = abs(dot(normalize(normal), normalize(toEye)));
  return color * (0.35 + 0.65 * facing) * 2.0 * exposure;
}

#endif
