// Material access for the visibility-buffer shaders: textures are sampled with analytic UV
// derivatives (set per pixel in gUvDx / gUvDy), and the triangle's attributes are interpolated
// from perspective-correct barycentrics.
#ifndef FGB_RENDERER_VISBUFFER_MATERIAL_GLSL
#define FGB_RENDERER_VISBUFFER_MATERIAL_GLSL

#include "visbuffer_triangle.glsl"
#include "surface_shading.glsl"

vec2 gUvDx = vec2(0.0);
vec2 gUvDy = vec2(0.0);

const float kMaxAnisotropy = 8.0;  // the material sampler's (gpu_upload.cpp)

// Anisotropic filtering done here rather than by the sampler: up to 8 trilinear taps along the
// footprint's major axis at the LOD of its minor extent. Sampling with explicit gradients is not
// anisotropic on every device (lavapipe filters textureGrad isotropically, its implicit-derivative
// texture() anisotropically), so this keeps the image the same wherever it runs, and close to the
// forward path's hardware filtering.
vec4 sampleSurfaceTexture(int textureIndex, vec2 uv) {
  uint index = uint(textureIndex);
  vec2 size = vec2(textureSize(fgbTextures[nonuniformEXT(index)], 0));
  float lengthX = length(gUvDx * size), lengthY = length(gUvDy * size);
  float major = max(lengthX, lengthY), minor = min(lengthX, lengthY);
  float taps = clamp(ceil(major / max(minor, 1e-8)), 1.0, kMaxAnisotropy);
  float lod = log2(max(major / taps, 1e-8));
  vec2 axis = lengthX > lengthY ? gUvDx : gUvDy;
  vec4 sum = vec4(0.0);
  for (float i = 0.0; i < taps; i += 1.0) {
    vec2 at = uv + axis * ((i + 0.5) / taps - 0.5);
    sum += textureLod(sampler2D(fgbTextures[nonuniformEXT(index)], fgbSamplers[pc.materialSampler]), at, lod);
  }
  return sum / taps;
}

// Tangents (vec4) and UVs (vec2) as one load per vertex of their whole element: their streams start
// 16-byte aligned (StagingBuilder in gpu_upload.cpp) and their strides are 16 and 8 bytes, so the
// float offsets in the push block are multiples of 4 and 2. SIMD CPU devices (lavapipe) load a
// vector element per invocation at once, where separate floats are separate loads.
vec4 fetchTangent(uint vertex) { return uintBitsToFloat(visUvec4sRead[pc.vertices].values[pc.tangents / 4u + vertex]); }
vec2 fetchUv(uint vertex) { return uintBitsToFloat(visUvec2sRead[pc.vertices].values[pc.uvs / 2u + vertex]); }

// UV and its per-pixel derivatives at the barycentrics b (with derivatives dbdx, dbdy), from the
// triangle's vertices in the attribute streams (streamVertices).
vec2 interpolateStreamUv(uvec3 vertices, vec3 b, vec3 dbdx, vec3 dbdy) {
  vec2 uv0 = fetchUv(vertices.x), uv1 = fetchUv(vertices.y), uv2 = fetchUv(vertices.z);
  gUvDx = uv0 * dbdx.x + uv1 * dbdx.y + uv2 * dbdx.z;
  gUvDy = uv0 * dbdy.x + uv1 * dbdy.y + uv2 * dbdy.z;
  return uv0 * b.x + uv1 * b.y + uv2 * b.z;
}
// The same from the triangle's cluster vertices (VisTriangle::vertices).
vec2 interpolateUv(uvec3 clusterVertices, vec3 b, vec3 dbdx, vec3 dbdy) {
  return interpolateStreamUv(streamVertices(clusterVertices), b, dbdx, dbdy);
}

vec3 interpolate3(vec3 a, vec3 b, vec3 c, vec3 w) { return a * w.x + b * w.y + c * w.z; }

// A triangle's surface at a pixel centre, shaded ("Material Shade" for the opaque pixel, and
// "Transparent Shade" for each kept transparent fragment): perspective-correct barycentrics and
// their screen derivatives analytically (homogeneous form, visbuffer.glsl), the attributes
// interpolated, then the forward path's shadeSurface: rgb pre-exposed, a the coverage (base alpha
// for blended materials). `p`: the surface point shaded (the debug views colour it).
vec4 shadeTrianglePixel(VisTriangle tri, uvec2 pixel, out SurfacePoint p) {
  vec2 size = viewportSize();
  Instance inst = fgbInstances[pc.instances].instances[tri.instance];
  ScreenTriangle screen = setupTriangle(modelViewProj(inst.model), tri.vertices);
  BarycentricFrame bf = barycentricFrame(screen.clip[0], screen.clip[1], screen.clip[2], size);
  vec3 b, dbdx, dbdy;
  barycentricsAt(bf, pixelNdc(pixel, size), b, dbdx, dbdy);

  uvec3 v = streamVertices(tri.vertices);
  vec3 world0 = (inst.model * vec4(clusterPosition(tri.vertices.x), 1.0)).xyz;
  vec3 world1 = (inst.model * vec4(clusterPosition(tri.vertices.y), 1.0)).xyz;
  vec3 world2 = (inst.model * vec4(clusterPosition(tri.vertices.z), 1.0)).xyz;
  p.worldPosition = interpolate3(world0, world1, world2, b);
  mat3 normalMatrix = mat3(inst.normalMatrix);
  p.normal = normalMatrix * interpolate3(fetchVec3(pc.vertices, pc.normals, v.x), fetchVec3(pc.vertices, pc.normals, v.y),
                                         fetchVec3(pc.vertices, pc.normals, v.z), b);
  vec4 t0 = fetchTangent(v.x), t1 = fetchTangent(v.y), t2 = fetchTangent(v.z);
  p.tangent = vec4(mat3(inst.model) * interpolate3(t0.xyz, t1.xyz, t2.xyz, b), t0.w * b.x + t1.w * b.y + t2.w * b.z);
  p.uv = safeUv(interpolateStreamUv(v, b, dbdx, dbdy));
  // The screen derivatives of the position, as forward.frag's cross(dFdx, dFdy) sees them.
  p.geometricNormal = cross(world0 * dbdx.x + world1 * dbdx.y + world2 * dbdx.z,
                            world0 * dbdy.x + world1 * dbdy.y + world2 * dbdy.z);
  p.frontFacing = framebufferFront(screen);
  p.fragCoord = vec2(pixel) + 0.5;

  FrameConstants frame = fgbFrames[pc.frame].frame;
  Material m = fgbMaterials[pc.materials].materials[inst.material];
  vec4 base = surfaceBaseColor(m, p.uv);
  return shadeSurface(frame, m, base, p, LightLists(pc.lights, pc.clusterCounts, pc.clusterIndices));
}

#endif
