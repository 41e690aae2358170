#version 460
// "Triangle Filter" (The Forge's triangle filtering): one workgroup per visible cluster, one
// invocation per triangle. A triangle is dropped when it is degenerate, behind the eye or beyond
// a frustum plane, back-facing (single-sided materials), or too small to cover a pixel centre.
// Survivors covering at most 8x8 pixel centres go to the small list (one raster thread each);
// larger ones to the large list with their 8x8-pixel tiles, which "Visibility Raster" spreads
// over one workgroup per tile so no thread walks a big triangle.
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer_triangle.glsl"

layout(local_size_x = 128) in;

const int kSmallPixels = 8;

bool outsideFrustum(vec4 c[3]) {
  // Each plane test holds for every w sign: the triangle's points are convex combinations.
  for (int axis = 0; axis < 2; ++axis) {
    if (c[0][axis] > c[0].w && c[1][axis] > c[1].w && c[2][axis] > c[2].w) return true;
    if (c[0][axis] < -c[0].w && c[1][axis] < -c[1].w && c[2][axis] < -c[2].w) return true;
  }
  if (c[0].z < 0.0 && c[1].z < 0.0 && c[2].z < 0.0) return true;
  return c[0].z > c[0].w && c[1].z > c[1].w && c[2].z > c[2].w;
}

void appendLarge(uint id, ivec4 pixels) {
  uvec2 firstTile = uvec2(pixels.xy) / kTileSize;
  uvec2 tiles = uvec2(pixels.zw) / kTileSize - firstTile + 1u;
  uint64_t totals = atomicAdd(visCounters[pc.counters].c.largeTotals, (uint64_t(1) << 40) | uint64_t(tiles.x * tiles.y));
  uint slot = uint(totals >> 40);
  if (slot >= pc.largeCapacity) {
    atomicAdd(visCounters[pc.counters].c.overflow, 1u);
    return;
  }
  uint firstJob = uint(totals & 0xffffffffffUL);
  visUvec4s[pc.largeList].values[slot] = uvec4(id, firstTile.x | (firstTile.y << 16), tiles.x | (tiles.y << 16), firstJob);
}

// What every invocation of the workgroup (one cluster of one instance) shares, loaded once.
shared mat4 sModelViewProj;
shared ClusterDraw sDraw;
shared uint sFirstIndex;
shared uint sTriangles;

void main() {
  uint clusterSlot = linearGroup();
  if (clusterSlot >= visCountersRead[pc.args].c.visibleClusters) return;  // uniform in the workgroup
  if (gl_LocalInvocationIndex == 0u) {
    loadFrameGlobals();
    ClusterDraw draw = visDraws[pc.draws].draws[fgbUintsRead[pc.visible].values[clusterSlot]];
    sDraw = draw;
    sModelViewProj = modelViewProj(fgbInstances[pc.instances].instances[draw.instance].model);
    sFirstIndex = visClusters[pc.clusters].clusters[draw.cluster].firstIndex;
    sTriangles = visClusters[pc.clusters].clusters[draw.cluster].triangleCount;
  }
  barrier();
  loadFrameGlobals();
  uint triangle = gl_LocalInvocationID.x;
  if (triangle >= sTriangles) return;
  VisTriangle tri;
  tri.instance = sDraw.instance;
  tri.flags = sDraw.flags;
  uint first = sFirstIndex + 3u * triangle;
  tri.vertices = uvec3(fgbUintsRead[pc.indices].values[first], fgbUintsRead[pc.indices].values[first + 1u],
                       fgbUintsRead[pc.indices].values[first + 2u]) + sDraw.firstVertex;
  if (tri.vertices.x == tri.vertices.y || tri.vertices.y == tri.vertices.z || tri.vertices.x == tri.vertices.z) return;
  ScreenTriangle t = setupTriangle(sModelViewProj, tri.vertices);
  if (t.clip[0].w <= 0.0 && t.clip[1].w <= 0.0 && t.clip[2].w <= 0.0) return;
  if (outsideFrustum(t.clip)) return;
  if (t.pixels.x > t.pixels.z || t.pixels.y > t.pixels.w) return;  // covers no pixel centre
  if (t.projected && t.area == 0) return;
  if ((tri.flags & kDrawSingleSided) != 0u) {
    bool front = framebufferFront(t) != ((tri.flags & kDrawMirrored) != 0u);
    if (!front) return;
  }
  uint id = (clusterSlot << kClusterTriangleBits) | triangle;
  ivec2 span = t.pixels.zw - t.pixels.xy + 1;
  if (t.projected && span.x <= kSmallPixels && span.y <= kSmallPixels && packable(t)) {
    uint slot = atomicAdd(visCounters[pc.counters].c.smallTriangles, 1u);
    uvec4 a, b;
    packSmallTriangle(t, id, (tri.flags & kDrawAlphaMasked) != 0u, a, b);
    visUvec4s[pc.smallList].values[2u * slot] = a;
    visUvec4s[pc.smallList].values[2u * slot + 1u] = b;
  } else {
    appendLarge(id, t.pixels);
  }
}
