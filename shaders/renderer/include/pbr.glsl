// Metallic-roughness PBR: GGX distribution, Smith (Schlick-GGX) geometry, Schlick Fresnel.
// NaN-safe for any input a material or mesh can produce: roughness 0 (clamped to kMinRoughness),
// the half vector of opposite view and light directions, cosines rounded past 1. Shared by the
// forward pass and the visibility buffer's material pass: keep lighting math here.
#ifndef FGB_RENDERER_PBR_GLSL
#define FGB_RENDERER_PBR_GLSL

struct Surface {
  vec3 albedo;
  float metallic;
  float roughness;
  vec3 normal;  // unit, world space
  vec3 view;    // unit, towards the camera
};

// Below this GGX's peak exceeds what half floats hold and the specular highlight of a point light
// vanishes between pixels; mirror-smooth materials are shaded as this smooth.
const float kMinRoughness = 0.04;

float distributionGgx(float nDotH, float roughness) {
  float a = roughness * roughness;
  float a2 = a * a;
  float d = nDotH * nDotH * (a2 - 1.0) + 1.0;
  return a2 / max(PI * d * d, 1e-7);
}

float geometrySchlickGgx(float nDotX, float k) { return nDotX / (nDotX * (1.0 - k) + k); }

float geometrySmith(float nDotV, float nDotL, float roughness) {
  float r = roughness + 1.0;
  float k = r * r / 8.0;
  return geometrySchlickGgx(nDotV, k) * geometrySchlickGgx(nDotL, k);
}

// pow() of a negative base is undefined: a cosine rounded just past 1 must not reach it.
vec3 fresnelSchlick(float cosTheta, vec3 f0) { return f0 + (1.0 - f0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0); }

// Outgoing radiance for light arriving from `toLight` (unit) with the given radiance.
vec3 shadeLight(Surface s, vec3 toLight, vec3 radiance) {
  vec3 h = safeNormalize(s.view + toLight, s.normal);  // view opposite the light: no half vector
  float nDotL = max(dot(s.normal, toLight), 0.0);
  float nDotV = max(dot(s.normal, s.view), 1e-4);
  if (!(nDotL > 0.0)) return vec3(0.0);  // also a NaN direction
  float roughness = clamp(s.roughness, kMinRoughness, 1.0);
  vec3 f0 = mix(vec3(0.04), s.albedo, s.metallic);
  vec3 f = fresnelSchlick(max(dot(h, s.view), 0.0), f0);
  float d = distributionGgx(min(max(dot(s.normal, h), 0.0), 1.0), roughness);
  float g = geometrySmith(nDotV, nDotL, roughness);
  vec3 specular = d * g * f / (4.0 * nDotV * nDotL + 1e-4);
  vec3 diffuse = (1.0 - f) * (1.0 - s.metallic) * s.albedo / PI;
  return (diffuse + specular) * radiance * nDotL;
}

#endif
