// Material access for the visibility-buffer shaders: textures are sampled with analytic UV
// derivatives (set per pixel in gUvDx / gUvDy), and the triangle's attributes are interpolated
// from perspective-correct barycentrics.
#ifndef FGB_RENDERER_VISBUFFER_MATERIAL_GLSL
#define FGB_RENDERER_VISBUFFER_MATERIAL_GLSL

#include "visbuffer_triangle.glsl"
#include "surface_shading.glsl"

vec2 gUvDx = vec2(0.0);
vec2 gUvDy = vec2(0.0);

vec4 sampleSurfaceTexture(int textureIndex, vec2 uv) {
  return textureGrad(sampler2D(fgbTextures[nonuniformEXT(uint(textureIndex))], fgbSamplers[pc.materialSampler]), uv,
                     gUvDx, gUvDy);
}

// UV and its per-pixel derivatives at the barycentrics b (with derivatives dbdx, dbdy).
vec2 interpolateUv(uvec3 vertices, vec3 b, vec3 dbdx, vec3 dbdy) {
  vec2 uv0 = fetchVec2(pc.vertices, pc.uvs, vertices.x);
  vec2 uv1 = fetchVec2(pc.vertices, pc.uvs, vertices.y);
  vec2 uv2 = fetchVec2(pc.vertices, pc.uvs, vertices.z);
  gUvDx = uv0 * dbdx.x + uv1 * dbdx.y + uv2 * dbdx.z;
  gUvDy = uv0 * dbdy.x + uv1 * dbdy.y + uv2 * dbdy.z;
  return uv0 * b.x + uv1 * b.y + uv2 * b.z;
}

#endif
