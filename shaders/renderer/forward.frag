#version 460
// "Mesh Render" fragment stage: metallic-roughness PBR with normal maps, alpha mask, emissive;
// point lights from the fragment's cluster list (or all lights when clustering is off) and the sun.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/forward_push.glsl"
#include "include/pbr.glsl"

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) flat in uint inMaterial;

layout(location = 0) out vec4 outColor;

// Texture coordinates: a NaN would make every lookup undefined.
vec2 safeUv() { return any(isnan(inUv)) || any(isinf(inUv)) ? vec2(0.0) : inUv; }

// An interpolated normal can vanish (opposite vertex normals across a crease): the surface is then
// shaded as facing the viewer. (Not the face normal from derivatives: it would be computed for
// every fragment, and derivatives are undefined inside the branch that needs it.)
vec3 shadingNormal(Material m, vec2 uv, vec3 towardsViewer) {
  float lengthSquared = dot(inNormal, inNormal);
  vec3 n = lengthSquared > 1e-20 ? inNormal * inversesqrt(lengthSquared) : towardsViewer;
  if (!gl_FrontFacing && lengthSquared > 1e-20) n = -n;
  if (m.normalTexture < 0 || dot(inTangent.xyz, inTangent.xyz) < 1e-12) return n;
  vec3 tangent = inTangent.xyz - n * dot(n, inTangent.xyz);
  if (dot(tangent, tangent) < 1e-12) return n;  // tangent along the normal: no tangent frame
  vec3 t = normalize(tangent);
  vec3 b = cross(n, t) * inTangent.w;
  vec3 tangentNormal = sampleMaterialTexture(m.normalTexture, pc.materialSampler, uv).xyz * 2.0 - 1.0;
  tangentNormal.xy *= m.emissive.w;
  return safeNormalize(mat3(t, b, n) * tangentNormal, n);
}

vec3 pointLight(Surface s, PointLight light) {
  vec3 toLight = light.positionRadius.xyz - inWorldPosition;
  float distance = length(toLight);
  float attenuation = pointLightAttenuation(distance, light.positionRadius.w);
  if (!(attenuation > 0.0)) return vec3(0.0);
  // A light on the surface (distance 0) lights it head-on rather than from a NaN direction.
  return shadeLight(s, safeNormalize(toLight, s.normal), light.color.rgb * attenuation);
}

// Point lights of this fragment's cluster; also returns how many were considered (debug view).
vec3 pointLights(FrameConstants frame, Surface s, out uint considered) {
  vec3 sum = vec3(0.0);
  if (pc.clusterCounts == FGB_NONE) {
    considered = frame.counts.x;
    for (uint i = 0; i < frame.counts.x; ++i) sum += pointLight(s, fgbLights[pc.lights].lights[i]);
    return sum;
  }
  float viewDepth = -(frame.view * vec4(inWorldPosition, 1.0)).z;
  uint cluster = clusterIndex(frame, gl_FragCoord.xy, viewDepth);
  considered = min(fgbUintsRead[pc.clusterCounts].values[cluster], frame.counts.z);
  uint base = cluster * frame.counts.z;
  for (uint i = 0; i < considered; ++i) {
    uint lightIndex = fgbUintsRead[pc.clusterIndices].values[base + i];
    sum += pointLight(s, fgbLights[pc.lights].lights[lightIndex]);
  }
  return sum;
}

void main() {
  FrameConstants frame = fgbFrames[pc.frame].frame;
  Material m = fgbMaterials[pc.materials].materials[inMaterial];
  vec2 uv = safeUv();
  vec4 base = m.baseColor;
  if (m.baseColorTexture >= 0) base *= sampleMaterialTexture(m.baseColorTexture, pc.materialSampler, uv);
  if (m.alphaMode == 1u && base.a < m.alphaCutoff) discard;

  Surface s;
  s.albedo = base.rgb;
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  if (m.metallicRoughnessTexture >= 0) {
    vec4 mr = sampleMaterialTexture(m.metallicRoughnessTexture, pc.materialSampler, uv);
    s.roughness *= mr.g;
    s.metallic *= mr.b;
  }
  s.roughness = clamp(s.roughness, kMinRoughness, 1.0);
  // Render space is camera-relative (the camera at the origin); a fragment at the camera sees +Z.
  s.view = safeNormalize(frame.cameraPosition.xyz - inWorldPosition, vec3(0.0, 0.0, 1.0));
  s.normal = shadingNormal(m, uv, s.view);

  uint considered = 0u;
  vec3 color = pointLights(frame, s, considered);
  if (frame.sunDirection.w > 0.0) color += shadeLight(s, -frame.sunDirection.xyz, frame.sunColor.rgb);
  color += frame.ambient.rgb * s.albedo;
  vec3 emissive = m.emissive.rgb;
  if (m.emissiveTexture >= 0) emissive *= sampleMaterialTexture(m.emissiveTexture, pc.materialSampler, uv).rgb;
  color += emissive;

  if (frame.counts.w == 1u) {
    // Light-complexity heat map: lights evaluated per fragment, 0 .. 16+.
    color = heatRamp(float(considered) / 16.0) * 4.0;
  }
  float alpha = m.alphaMode == 2u ? base.a : 1.0;
  // Pre-exposed (see ExposureGpu) and clamped to R16F's range: too bright saturates, never Inf.
  outColor = vec4(min(color * preExposure(frame), vec3(kHalfMax)), alpha);
  if ((pc.flags & 4u) != 0u && ivec2(gl_FragCoord.xy) == ivec2(frame.viewport.xy) / 2) {
    outColor.rgb = vec3(uintBitsToFloat(0x7fc00000u));  // debug.inject_nan: a NaN at the centre pixel
  }
}
