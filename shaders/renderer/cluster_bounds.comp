#version 460
// "Cluster Bounds": the view-space AABB of every cluster (16x16-pixel tile x exponential depth
// slice z = near * (far/near)^(slice/slices)). The job dispatches only when the projection changed.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "renderer/shared/lighting.h"

layout(local_size_x = FGB_CLUSTER_BOUNDS_GROUP_SIZE) in;

layout(push_constant) uniform Push { ClusterBoundsPush pc; };

// View-space point on the ray through a pixel, at view depth `depth` (positive distance).
vec3 pointAtDepth(FrameConstants frame, vec2 pixel, float depth) {
  vec2 ndc = pixel * frame.viewport.zw * 2.0 - 1.0;
  vec4 onNear = frame.invProj * vec4(ndc, 1.0, 1.0);  // reversed-Z: depth 1 is the near plane
  vec3 ray = onNear.xyz / onNear.w;
  return ray * (depth / -ray.z);
}

void main() {
  uint cluster = gl_GlobalInvocationID.x;
  if (cluster >= pc.clusterCount) return;
  FrameConstants frame = fgbFrames[pc.frame].frame;
  uvec3 grid = frame.clusterGrid.xyz;
  uint tileX = cluster % grid.x;
  uint tileY = (cluster / grid.x) % grid.y;
  uint slice = cluster / (grid.x * grid.y);
  float near = frame.depthRange.x;
  float ratio = frame.depthRange.y / near;
  float depth0 = near * pow(ratio, float(slice) / float(grid.z));
  float depth1 = near * pow(ratio, float(slice + 1u) / float(grid.z));
  vec2 pixelMin = vec2(tileX, tileY) * float(frame.clusterGrid.w);
  vec2 pixelMax = min(pixelMin + float(frame.clusterGrid.w), frame.viewport.xy);

  vec3 boxMin = vec3(1e30);
  vec3 boxMax = vec3(-1e30);
  for (int corner = 0; corner < 8; ++corner) {
    vec2 pixel = vec2((corner & 1) != 0 ? pixelMax.x : pixelMin.x, (corner & 2) != 0 ? pixelMax.y : pixelMin.y);
    vec3 p = pointAtDepth(frame, pixel, (corner & 4) != 0 ? depth1 : depth0);
    boxMin = min(boxMin, p);
    boxMax = max(boxMax, p);
  }
  fgbVec4s[pc.bounds].values[2u * cluster] = vec4(boxMin, 0.0);
  fgbVec4s[pc.bounds].values[2u * cluster + 1u] = vec4(boxMax, 0.0);
}
