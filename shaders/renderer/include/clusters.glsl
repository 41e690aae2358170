// The cooked clusters as the cluster-drawing paths read them (the visibility buffer's compute
// passes, shaders/renderer/visbuffer/, and the meshlet path's task and mesh shaders,
// shaders/renderer/meshlets/): their buffers (structs in renderer/shared/visbuffer.h), the
// vertex fetches, and the per-cluster tests both paths apply the same way: the LOD cut, the
// instance box and cluster sphere against the frustum, and the normal cone.
#ifndef FGB_RENDERER_CLUSTERS_GLSL
#define FGB_RENDERER_CLUSTERS_GLSL

// visbuffer.h declares VisCounters with a 64-bit member: the types must parse, but a shader that
// never uses the struct declares no 64-bit capability (the meshlet path's shaders do not).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "common.glsl"
#include "renderer/shared/visbuffer.h"

FGB_READONLY_STORAGE_BUFFER(ClusterBlock, visClusters) { ClusterData clusters[]; } visClusters[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(ClusterDrawBlock, visDraws) { ClusterDraw draws[]; } visDraws[FGB_MAX_STORAGE_BUFFERS];
// The cluster vertex stream (uvec4 per cluster vertex: its position's float bits, w: its vertex in
// the attribute streams), and other uvec4 lists.
FGB_READONLY_STORAGE_BUFFER(Uvec4ReadBlock, visUvec4sRead) { uvec4 values[]; } visUvec4sRead[FGB_MAX_STORAGE_BUFFERS];

// A packed cluster triangle (scene::packClusterTriangle: three 8-bit cluster-local indices) as
// cluster vertices (indices into the scene-wide cluster vertex stream).
uvec3 clusterTriangleVertices(uint packed, uint firstVertex) {
  return uvec3(packed & 0xffu, (packed >> 8) & 0xffu, packed >> 16) + firstVertex;
}

// Vertex attribute fetches from the scene's vertex buffer (float streams at the given float offsets).
vec3 fetchVec3(uint vertexBuffer, uint streamOffset, uint vertex) {
  uint at = streamOffset + 3u * vertex;
  return vec3(uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at]), uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at + 1u]),
              uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at + 2u]));
}
vec4 fetchVec4(uint vertexBuffer, uint streamOffset, uint vertex) {
  uint at = streamOffset + 4u * vertex;
  return vec4(uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at]), uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at + 1u]),
              uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at + 2u]), uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at + 3u]));
}
vec2 fetchVec2(uint vertexBuffer, uint streamOffset, uint vertex) {
  uint at = streamOffset + 2u * vertex;
  return vec2(uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at]), uintBitsToFloat(fgbUintsRead[vertexBuffer].values[at + 1u]));
}

// Depth key (the visibility words' high 32 bits, the HiZ pyramid's texels): larger = nearer,
// never 0 for a depth in range.
uint depthKey(float z, bool reversedZ) {
  return reversedZ ? floatBitsToUint(max(z, 1e-30)) : 0xffffffffu - floatBitsToUint(max(z, 0.0));
}
float depthFromKey(uint key, bool reversedZ) {
  return reversedZ ? uintBitsToFloat(key) : uintBitsToFloat(0xffffffffu - key);
}

// The largest axis scale of an instance's model matrix (bounding spheres scale by it).
float maxScale(mat4 model) {
  return sqrt(max(dot(model[0].xyz, model[0].xyz), max(dot(model[1].xyz, model[1].xyz), dot(model[2].xyz, model[2].xyz))));
}

// Against the frame's six frustum planes (render space, inside: dot(n, p) + d >= 0); `frame` is
// the FrameConstants' storage-buffer index.
bool boxInside(uint frame, vec3 boxMin, vec3 boxMax) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = fgbFrames[frame].frame.frustumPlanes[i];
    vec3 positive = mix(boxMin, boxMax, greaterThanEqual(p.xyz, vec3(0.0)));
    if (dot(p.xyz, positive) + p.w < 0.0) return false;
  }
  return true;
}

bool sphereInside(uint frame, vec3 center, float radius) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = fgbFrames[frame].frame.frustumPlanes[i];
    if (dot(p.xyz, center) + p.w < -radius) return false;
  }
  return true;
}

// proj[1][1] is cot(fov / 2) (negated: Y flips), so a length l at distance d spans
// l / d * |proj[1][1]| * height / 2 pixels of the scene passes (viewport: their size).
float pixelsPerUnit(uint frame) {
  return abs(fgbFrames[frame].frame.proj[1][1]) * 0.5 * fgbFrames[frame].frame.viewport.y;
}

// A mesh-local error at a mesh-local sphere, in scene pixels: the error scaled like the instance,
// over the distance from the eye to the sphere's nearest point. A sphere reaching in front of the
// near plane (in view depth) projects an unbounded error (level 0, whose error is 0, excepted), so
// such groups are refined: a coarse level's large triangles with a corner behind the eye do not
// reach the visibility buffer (without this the no-particles floor, whose coarse groups hold the
// camera's feet, vanished; level 0's small triangles rarely have such a corner where it shows).
// A sphere holding another is no farther and reaches no less near, so a larger error there never
// projects smaller: the DAG's monotonic errors stay monotonic on screen. Render space is anchored
// within a cell of the camera (render_space.hpp), so this holds at any scene offset (scene.offset=1e7).
float projectedError(vec4 sphere, float error, mat4 model, float scale, uint frame) {
  if (error <= 0.0) return 0.0;
  vec3 center = (model * vec4(sphere.xyz, 1.0)).xyz;
  float radius = sphere.w * scale;
  float nearestDepth = -(fgbFrames[frame].frame.view * vec4(center, 1.0)).z - radius;  // the view looks down -z
  if (nearestDepth <= fgbFrames[frame].frame.depthRange.x) return 3.0e38;
  float distance = length(center - fgbFrames[frame].frame.cameraPosition.xyz) - radius;
  return error * scale * pixelsPerUnit(frame) / distance;
}

// Whether the cluster belongs to this view's LOD cut at `threshold` scene pixels
// (scene::inLodCut on projected errors; threshold 0: level 0 only). A group's members and the
// clusters made from it compute the very same value from the same group fields, so either all of
// the members or all of those clusters are drawn.
bool lodInCut(ClusterData cluster, mat4 model, float scale, uint frame, float threshold) {
  if (threshold <= 0.0) return cluster.lodLevel == 0u;
  return projectedError(cluster.lodSphere, cluster.lodError, model, scale, frame) <= threshold &&
         projectedError(cluster.parentSphere, cluster.parentError, model, scale, frame) > threshold;
}

// Whether a single-sided cluster (ClusterDraw::flags) faces away from the eye entirely
// (meshoptimizer's cone test); `center` and `radius` are its render-space bounding sphere.
bool clusterConeCulled(ClusterData cluster, uint flags, Instance inst, vec3 center, float radius, uint frame) {
  if ((flags & (kClusterSingleSided | kClusterConeUsable)) != (kClusterSingleSided | kClusterConeUsable) ||
      cluster.cone.w >= 1.0)
    return false;
  // Front is defined in object space (glTF), so the axis transforms as a normal.
  vec3 axis = normalize(mat3(inst.normalMatrix) * cluster.cone.xyz);
  vec3 fromEye = center - fgbFrames[frame].frame.cameraPosition.xyz;
  return dot(fromEye, axis) >= cluster.cone.w * length(fromEye) + radius;
}

#endif
