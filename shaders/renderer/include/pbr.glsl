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
//
// The specular term D G F / (4 nDotV nDotL), with the GGX distribution D = a2 / (PI dd^2) and the
// Smith Schlick-GGX geometry G = G1(nDotV) G1(nDotL), G1(x) = x / (x (1 - k) + k), simplifies to
// F a2 / (4 PI dd^2 gV gL) with gX = x (1 - k) + k: one division per light, by a product bounded
// away from zero (dd >= a2 >= kMinRoughness^4, gX >= k >= 1/8). What depends only on the surface
// (a2, k, gV, the diffuse colour) the compiler hoists out of the light loop.
vec3 shadeLight(Surface s, vec3 toLight, vec3 radiance) {
  float nDotL = dot(s.normal, toLight);
  if (!(nDotL > 0.0)) return vec3(0.0);  // behind the surface, and a zero or NaN direction
  // The view exactly opposite the light has no half vector: h = 0 shades it as grazing.
  vec3 halfSum = s.view + toLight;
  vec3 h = halfSum * inversesqrt(max(dot(halfSum, halfSum), 1e-30));
  float nDotV = max(dot(s.normal, s.view), 1e-4);
  float nDotH = clamp(dot(s.normal, h), 0.0, 1.0);
  float a = s.roughness * s.roughness;
  float a2 = a * a;
  float dd = nDotH * nDotH * (a2 - 1.0) + 1.0;
  float r = s.roughness + 1.0;
  float k = r * r / 8.0;
  float gV = nDotV * (1.0 - k) + k;
  float gL = nDotL * (1.0 - k) + k;
  vec3 f = fresnelSchlick(dot(h, s.view), mix(vec3(0.04), s.albedo, s.metallic));
  vec3 specular = f * (a2 / (4.0 * PI * dd * dd * gV * gL));
  vec3 diffuse = (1.0 - f) * ((1.0 - s.metallic) / PI) * s.albedo;
  return (diffuse + specular) * radiance * nDotL;
}

#endif
