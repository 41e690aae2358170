#version 460
// "Material Shade": one invocation per pixel. It decodes the pixel's visibility word, rebuilds
// the triangle from its id (visible cluster -> instance, cluster -> three vertices), computes
// perspective-correct barycentrics and their screen derivatives analytically (homogeneous form,
// visbuffer.glsl), interpolates the attributes and shades them with the same code as the forward
// path (surface_shading.glsl), writing the HDR target. It also writes the pixel's depth (the far
// value where nothing was drawn), which the transparent and particle passes test their fragments
// against (include/opaque_depth.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "../include/visbuffer_material.glsl"

layout(local_size_x = FGB_VIS_SHADE_GROUP_SIZE, local_size_y = FGB_VIS_SHADE_GROUP_SIZE) in;

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) uniform writeonly image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

vec3 interpolate3(vec3 a, vec3 b, vec3 c, vec3 w) { return a * w.x + b * w.y + c * w.z; }

#ifdef FGB_DEBUG_VIEWS
#include "../include/debug_views.glsl"

vec3 debugViewColor(FrameConstants frame, uint drawIndex, SurfacePoint p) {
  ClusterDraw draw = visDraws[pc.draws].draws[drawIndex];
  uint lodLevel = visClusters[pc.clusters].clusters[draw.cluster].lodLevel;
  return debugViewColor(frame.counts.w, lodLevel, draw.cluster, draw.instance, p.normal,
                        frame.cameraPosition.xyz - p.worldPosition, preExposure(frame));
}
#endif

void main() {
  loadFrameGlobals();
  uvec2 pixel = gl_GlobalInvocationID.xy;
  uvec2 size = uvec2(viewportSize());
  if (any(greaterThanEqual(pixel, size))) return;
  uint index = pixel.y * size.x + pixel.x;
  uint64_t word = visWordAt(pc.words, ivec2(pixel), size.x);
  if (word == 0ul) {
    visFloats[pc.depthOut].values[index] = reversedZ() ? 0.0 : 1.0;
    imageStore(fgbImagesRgba16f[pc.hdr], ivec2(pixel), pc.background);
    return;
  }
  visFloats[pc.depthOut].values[index] = depthFromKey(uint(word >> 32), reversedZ());
  uint id = uint(word);
  uint drawIndex = id >> kClusterTriangleBits;
  VisTriangle tri = visTriangle(drawIndex, id & ((1u << kClusterTriangleBits) - 1u), pc.draws, pc.clusters, pc.indices);
  Instance inst = fgbInstances[pc.instances].instances[tri.instance];
  ScreenTriangle screen = setupTriangle(modelViewProj(inst.model), tri.vertices);
  BarycentricFrame bf = barycentricFrame(screen.clip[0], screen.clip[1], screen.clip[2], vec2(size));
  vec3 b, dbdx, dbdy;
  barycentricsAt(bf, pixelNdc(pixel, vec2(size)), b, dbdx, dbdy);

  uvec3 v = streamVertices(tri.vertices);
  SurfacePoint p;
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
  vec4 color = shadeSurface(frame, m, base, p, LightLists(pc.lights, pc.clusterCounts, pc.clusterIndices));
#ifdef FGB_DEBUG_VIEWS
  if (frame.counts.w >= kDebugViewLod) color.rgb = debugViewColor(frame, drawIndex, p);
#endif
  if ((pc.flags & kFlagInjectBias) != 0u) color.rgb += kInjectedBias;  // debug.inject_bias
  imageStore(fgbImagesRgba16f[pc.hdr], ivec2(pixel), vec4(color.rgb, 1.0));  // alpha > 0: metered geometry
}
