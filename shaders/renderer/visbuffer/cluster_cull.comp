#version 460
// "Cluster Cull": one invocation per cluster, of every LOD level, of every opaque or alpha-masked
// instance. First the LOD cut (lodInCut): the cluster is kept when its own error projects to at
// most the threshold and its parent group's error to more, so of each mesh one consistent cut is
// drawn (scene::Cluster). Then the instance's world AABB and the cluster's bounding sphere are
// tested against the six frustum
// planes; clusters of single-sided materials are also dropped when their normal cone faces away
// from the camera (meshoptimizer's cone test). Survivors are appended to the visible-cluster list
// ("Triangle Filter" runs one workgroup per entry). Counters were zeroed by "Visibility Clear".
// With render.occlusion=1 (phase 1 of two-phase occlusion culling) survivors whose sphere is
// hidden behind last frame's HiZ pyramid go to the occlusion candidates instead, which
// "Cluster Cull (late)" re-tests against this frame's (cluster_cull_late.comp).
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer.glsl"
#include "hiz_occlusion.glsl"

layout(local_size_x = FGB_VIS_CULL_GROUP_SIZE) in;

layout(push_constant) uniform Push { ClusterCullPush pc; };

// The frame's frustum planes (render space), from its FrameConstants.
vec4 plane(int i) { return fgbFrames[pc.frame].frame.frustumPlanes[i]; }

bool boxInside(vec3 boxMin, vec3 boxMax) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = plane(i);
    vec3 positive = mix(boxMin, boxMax, greaterThanEqual(p.xyz, vec3(0.0)));
    if (dot(p.xyz, positive) + p.w < 0.0) return false;
  }
  return true;
}

bool sphereInside(vec3 center, float radius) {
  for (int i = 0; i < 6; ++i) {
    vec4 p = plane(i);
    if (dot(p.xyz, center) + p.w < -radius) return false;
  }
  return true;
}

// render.occlusion and a pyramid from last frame (none on the first frame: the frame's flag).
bool hizUsable() {
  return (pc.drawCount & kCullOcclusion) != 0u && (fgbFrames[pc.frame].frame.step.y & kFrameHizValid) != 0u;
}

// A mesh-local error at a mesh-local sphere, in scene pixels: the error scaled like the instance,
// over the distance from the eye to the sphere's nearest point. A sphere reaching in front of the
// near plane (in view depth) projects an unbounded error (level 0, whose error is 0, excepted), so
// such groups are refined: a coarse level's large triangles with a corner behind the eye do not
// reach the visibility buffer (without this the no-particles floor, whose coarse groups hold the
// camera's feet, vanished; level 0's small triangles rarely have such a corner where it shows).
// A sphere holding another is no farther and reaches no less near, so a larger error there never
// projects smaller: the DAG's monotonic errors stay monotonic on screen. Render space is
// camera-relative, so this holds at any scene offset (scene.offset=1e7).
float projectedError(vec4 sphere, float error, mat4 model, float scale, uint frame) {
  if (error <= 0.0) return 0.0;
  vec3 center = (model * vec4(sphere.xyz, 1.0)).xyz;
  float radius = sphere.w * scale;
  float nearestDepth = -(fgbFrames[frame].frame.view * vec4(center, 1.0)).z - radius;  // the view looks down -z
  if (nearestDepth <= fgbFrames[frame].frame.depthRange.x) return 3.0e38;
  float distance = length(center - fgbFrames[frame].frame.cameraPosition.xyz) - radius;
  // proj[1][1] is cot(fov / 2) (negated: Y flips), so a length l at distance d spans
  // l / d * |proj[1][1]| * height / 2 pixels of the scene passes (viewport: their size).
  float pixelsPerUnit = abs(fgbFrames[frame].frame.proj[1][1]) * 0.5 * fgbFrames[frame].frame.viewport.y;
  return error * scale * pixelsPerUnit / distance;
}

// Whether the cluster belongs to this view's LOD cut (scene::inLodCut on projected errors). A
// group's members and the clusters made from it compute the very same value from the same group
// fields, so either all of the members or all of those clusters are drawn.
bool lodInCut(ClusterData cluster, mat4 model, float scale, uint frame) {
  if (pc.lodThreshold <= 0.0) return cluster.lodLevel == 0u;
  return projectedError(cluster.lodSphere, cluster.lodError, model, scale, frame) <= pc.lodThreshold &&
         projectedError(cluster.parentSphere, cluster.parentError, model, scale, frame) > pc.lodThreshold;
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= (pc.drawCount & kCullDrawCountMask)) return;
  uint frame = pc.frame;
  ClusterDraw draw = visDraws[pc.draws].draws[id];
  Instance inst = fgbInstances[pc.instances].instances[draw.instance];
  if (!boxInside(inst.boundsMin.xyz, inst.boundsMax.xyz)) return;
  ClusterData cluster = visClusters[pc.clusters].clusters[draw.cluster];
  float scale = maxScale(inst.model);
  if (!lodInCut(cluster, inst.model, scale, frame)) return;
  vec3 center = (inst.model * vec4(cluster.sphere.xyz, 1.0)).xyz;
  float radius = cluster.sphere.w * scale;
  if (!sphereInside(center, radius)) return;
  if ((draw.flags & (kClusterSingleSided | kClusterConeUsable)) == (kClusterSingleSided | kClusterConeUsable) &&
      cluster.cone.w < 1.0) {
    // Front is defined in object space (glTF), so the axis transforms as a normal.
    vec3 axis = normalize(mat3(inst.normalMatrix) * cluster.cone.xyz);
    vec3 fromEye = center - fgbFrames[frame].frame.cameraPosition.xyz;
    if (dot(fromEye, axis) >= cluster.cone.w * length(fromEye) + radius) return;
  }
  bool holdBack = (pc.drawCount & kCullHoldBackOdd) != 0u && (id & 1u) != 0u;
  if (holdBack || (hizUsable() &&
                   hizOccluded(pc.occlusion & 0xffffu, pc.frame, center, radius,
                               (pc.drawCount & kCullReversedZ) != 0u))) {
    uint candidate = atomicAdd(visCounters[pc.counters].c.occluded, 1u);
    fgbUints[pc.occlusion >> 16].values[candidate] = id;
    return;
  }
  uint slot = atomicAdd(visCounters[pc.counters].c.visibleClusters, 1u);
  fgbUints[pc.visible].values[slot] = id;
  atomicAdd(visCounters[pc.counters].c.lodClusters[min(cluster.lodLevel, FGB_VIS_LOD_STAT_LEVELS - 1)], 1u);
}
