// The compute transparent passes' common parts ("Transparent Raster", "Transparent Shade";
// render.transparent=compute; push-field meanings in renderer/shared/transparent.h): the K-buffer
// and the triangle behind a fragment id.
//
// A K-buffer slot holds (key << 32 | id) with key = ~depthKey(z): smaller is nearer, so a 64-bit
// atomicMin keeps the nearest, and an equal depth goes to the smaller id (no dependence on the
// order atomics land in). kEmpty (all ones) is larger than every fragment: depthKey is never 0 for
// a depth in range. The id is (packed draw << kClusterTriangleBits) | triangle in its cluster.
#ifndef FGB_RENDERER_TRANSPARENT_COMPUTE_GLSL
#define FGB_RENDERER_TRANSPARENT_COMPUTE_GLSL

#include "visbuffer_triangle.glsl"
#include "renderer/shared/transparent.h"

#define TRANSPARENT_K FGB_TRANSPARENT_K
const uint64_t kEmpty = 0xffffffffffffffffUL;

// "Transparent Cluster Cull"'s packed draws in the cluster form (kTransparentCullClusterIds).
FGB_READONLY_STORAGE_BUFFER(TransparentDrawBlock, transparentDraws) { DrawCommand draws[]; } transparentDraws[FGB_MAX_STORAGE_BUFFERS];

uint pixelCount() { return uint(viewportSize().x) * uint(viewportSize().y); }
uint kSlotIndex(uint slot, uint pixelIndex) { return slot * pixelCount() + pixelIndex; }

// Shade tiles (FGB_TRANSPARENT_SHADE_GROUP_SIZE pixels square), row-major over the viewport; a
// tile's flag word follows the K-buffer's planes (kEmpty: not listed this frame).
uint tilesAcross() { return (uint(viewportSize().x) + FGB_TRANSPARENT_SHADE_GROUP_SIZE - 1u) / FGB_TRANSPARENT_SHADE_GROUP_SIZE; }
uint tileFlagIndex(uint tile) { return TRANSPARENT_K * pixelCount() + tile; }

uint64_t fragmentWord(float z, uint id) { return (uint64_t(~depthKey(z, reversedZ())) << 32) | uint64_t(id); }

// A fragment id's triangle (VisTriangle, as the visibility buffer's shaders take it): the draw's
// instance, and its cluster's triangle.
VisTriangle transparentTriangle(uint id) {
  DrawCommand draw = transparentDraws[pc.draws].draws[id >> kClusterTriangleBits];
  ClusterData cluster = visClusters[pc.clusters].clusters[draw.firstIndex];
  uint packed = fgbUintsRead[pc.indices].values[cluster.firstTriangle + (id & ((1u << kClusterTriangleBits) - 1u))];
  VisTriangle t;
  t.instance = draw.firstInstance;
  t.flags = 0u;
  t.vertices = clusterTriangleVertices(packed, cluster.firstVertex);
  return t;
}

#endif
