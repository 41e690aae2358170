// Metallic-roughness PBR: GGX distribution, Smith (Schlick-GGX) geometry, Schlick Fresnel.
// NaN-safe for any input a material or mesh can produce: roughness 0 (shadeSurface clamps it to
// kMinRoughness), a light with no direction, the half vector of opposite view and light directions,
// cosines rounded past 1. Shared by the forward pass and the visibility buffer's material pass:
// keep lighting math here.
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

// (1 - cos)^5 as products: exact for every cosine, where pow() of a negative base (a cosine rounded
// just past 1) is undefined; the clamp is free on GPUs (a saturate modifier).
vec3 fresnelSchlick(float cosTheta, vec3 f0) {
  float x = clamp(1.0 - cosTheta, 0.0, 1.0);
  float x2 = x * x;
  return f0 + (1.0 - f0) * (x2 * x2 * x);
}

// Outgoing radiance for light arriving from `toLight` (unit, or zero when the light has no
// direction) with the given radiance. s.roughness must lie in [kMinRoughness, 1]: shadeSurface
// clamps it once per pixel, not once per light.
vec3 shadeLight(Surface s, vec3 toLight, vec3 radiance) {
  float nDotL = max(dot(s.normal, toLight), 0.0);
  if (!(nDotL > 0.0)) return vec3(0.0);  // also a zero or NaN direction
  // The view exactly opposite the light has no half vector: h = 0 shades it as grazing.
  vec3 halfSum = s.view + toLight;
  vec3 h = halfSum * inversesqrt(max(dot(halfSum, halfSum), 1e-30));
  float nDotV = max(dot(s.normal, s.view), 1e-4);
  vec3 f0 = mix(vec3(0.04), s.albedo, s.metallic);
  vec3 f = fresnelSchlick(dot(h, s.view), f0);
  float d = distributionGgx(clamp(dot(s.normal, h), 0.0, 1.0), s.roughness);
  float g = geometrySmith(nDotV, nDotL, s.roughness);
  vec3 specular = d * g * f / (4.0 * nDotV * nDotL + 1e-4);
  vec3 diffuse = (1.0 - f) * (1.0 - s.metallic) * s.albedo / PI;
  return (diffuse + specular) * radiance * nDotL;
}

#endif
