// Surface shading shared by the forward fragment shader ("Mesh Render", forward.frag) and the
// visibility-buffer path ("Material Shade", material_shade.comp): metallic-roughness PBR with
// normal maps and emissive, point lights from the pixel's cluster list (or every light when
// clustering is off), the sun, ambient and the light-complexity debug view. Both paths shade
// through this one file so their images can only differ in what reaches it (visibility, the
// interpolated attributes, texture LOD).
//
// The including shader defines how material textures are sampled (forward: implicit derivatives;
// Material Shade: analytic ones):
//   vec4 sampleSurfaceTexture(int textureIndex, vec2 uv);
#ifndef FGB_RENDERER_SURFACE_SHADING_GLSL
#define FGB_RENDERER_SURFACE_SHADING_GLSL

#include "common.glsl"
#include "pbr.glsl"
#include "renderer/shared/debug.h"

vec4 sampleSurfaceTexture(int textureIndex, vec2 uv);

// The interpolated attributes of one surface point (world space).
struct SurfacePoint {
  vec3 worldPosition;    // render space (world axes, anchored near the camera)
  vec3 normal;           // not normalised
  vec4 tangent;          // xyz not normalised, w: bitangent sign
  vec2 uv;
  bool frontFacing;
  vec2 fragCoord;        // pixel position (centre at +0.5), for the cluster lookup
  vec3 geometricNormal;  // the face's own normal (any length, may vanish): the fallback when the
                         // interpolated normal vanishes (opposite vertex normals across a crease)
};

// Texture coordinates: a NaN would make every lookup undefined.
vec2 safeUv(vec2 uv) { return any(isnan(uv)) || any(isinf(uv)) ? vec2(0.0) : uv; }

// Where the light lists live (bindless storage-buffer indices); clusterCounts FGB_NONE: every light.
struct LightLists {
  uint lights;
  uint clusterCounts;
  uint clusterIndices;
};

// Base colour (factor x texture); its alpha decides alpha masking and blending.
vec4 surfaceBaseColor(Material m, vec2 uv) {
  vec4 base = m.baseColor;
  if (m.baseColorTexture >= 0) base *= sampleSurfaceTexture(m.baseColorTexture, uv);
  return base;
}

// The geometric normal's derivatives vanish too on a degenerate (edge-on) triangle: then the view
// direction stands in.
vec3 shadingNormal(Material m, SurfacePoint p, vec3 towardsViewer) {
  vec3 n = safeNormalize(p.normal, safeNormalize(p.geometricNormal, towardsViewer));
  if (!p.frontFacing) n = -n;
  if (m.normalTexture < 0 || dot(p.tangent.xyz, p.tangent.xyz) < 1e-12) return n;
  vec3 tangent = p.tangent.xyz - n * dot(n, p.tangent.xyz);
  if (dot(tangent, tangent) < 1e-12) return n;  // tangent along the normal: no tangent frame
  vec3 t = normalize(tangent);
  vec3 b = cross(n, t) * p.tangent.w;
  vec3 tangentNormal = sampleSurfaceTexture(m.normalTexture, p.uv).xyz * 2.0 - 1.0;
  tangentNormal.xy *= m.emissive.w;
  return safeNormalize(mat3(t, b, n) * tangentNormal, n);
}

vec3 pointLight(Surface s, vec3 worldPosition, PointLight light) {
  vec3 toLight = light.positionRadius.xyz - worldPosition;
  // One reciprocal square root gives the distance, the unit direction and the attenuation's 1/d.
  // A light on the surface (distance 0) gives a zero direction, which shadeLight turns away like a
  // light behind the surface, instead of a NaN one.
  float distanceSquared = dot(toLight, toLight);
  float inverseDistance = inversesqrt(max(distanceSquared, 1e-30));
  float attenuation = pointLightAttenuation(distanceSquared * inverseDistance, inverseDistance, light.color.w);
  if (!(attenuation > 0.0)) return vec3(0.0);
  return shadeLight(s, toLight * inverseDistance, light.color.rgb * attenuation);
}

// Point lights of this point's cluster; also returns how many were considered (debug view).
vec3 pointLights(FrameConstants frame, Surface s, SurfacePoint p, LightLists lists, out uint considered) {
  vec3 sum = vec3(0.0);
  if (lists.clusterCounts == FGB_NONE) {
    considered = frame.counts.x;
    for (uint i = 0; i < frame.counts.x; ++i) sum += pointLight(s, p.worldPosition, fgbLights[lists.lights].lights[i]);
    return sum;
  }
  float viewDepth = -(frame.view * vec4(p.worldPosition, 1.0)).z;
  uint cluster = clusterIndex(frame, p.fragCoord, viewDepth);
  considered = min(fgbUintsRead[lists.clusterCounts].values[cluster], frame.counts.z);
  uint base = cluster * frame.counts.z;
  for (uint i = 0; i < considered; ++i) {
    uint lightIndex = fgbUintsRead[lists.clusterIndices].values[base + i];
    sum += pointLight(s, p.worldPosition, fgbLights[lists.lights].lights[lightIndex]);
  }
  return sum;
}

// Radiance leaving the surface towards the camera (rgb), pre-exposed (ExposureGpu) and clamped to
// R16F's range (too bright saturates, never Inf), and its coverage (a: base alpha for blended
// materials, else 1). `base` is surfaceBaseColor(m, p.uv); p.uv is safeUv()'s.
vec4 shadeSurface(FrameConstants frame, Material m, vec4 base, SurfacePoint p, LightLists lists) {
  Surface s;
  s.albedo = base.rgb;
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  if (m.metallicRoughnessTexture >= 0) {
    vec4 mr = sampleSurfaceTexture(m.metallicRoughnessTexture, p.uv);
    s.roughness *= mr.g;
    s.metallic *= mr.b;
  }
  s.roughness = clamp(s.roughness, kMinRoughness, 1.0);
  // The eye is at cameraPosition (render space is anchored near it, not at it); a point at the eye
  // sees +Z.
  s.view = safeNormalize(frame.cameraPosition.xyz - p.worldPosition, vec3(0.0, 0.0, 1.0));
  s.normal = shadingNormal(m, p, s.view);

  uint considered = 0u;
  vec3 color = pointLights(frame, s, p, lists, considered);
  if (frame.sunDirection.w > 0.0) color += shadeLight(s, -frame.sunDirection.xyz, frame.sunColor.rgb);
  color += frame.ambient.rgb * s.albedo;
  vec3 emissive = m.emissive.rgb;
  if (m.emissiveTexture >= 0) emissive *= sampleSurfaceTexture(m.emissiveTexture, p.uv).rgb;
  color += emissive;

  if (frame.counts.w == kDebugViewLightComplexity) {
    // Light-complexity heat map: lights evaluated per pixel, 0 .. 16+.
    color = heatRamp(float(considered) / 16.0) * 4.0;
  }
  float alpha = m.alphaMode == 2u ? base.a : 1.0;
  return vec4(min(color * preExposure(frame), vec3(kHalfMax)), alpha);
}

#endif
