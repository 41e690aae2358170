#version 460
// "Triangle Filter" (The Forge's triangle filtering): one workgroup per visible cluster, its (at
// most 128) triangles shared among the invocations (see main). A triangle is dropped when it is
// degenerate, behind the eye or beyond a frustum plane, back-facing (single-sided materials), or
// too small to cover a pixel centre.
// Survivors covering at most 8x8 pixel centres go to the small list (one raster thread each);
// larger ones go to the large list set up (packLargeTriangle), and their 8x8-pixel tiles, in
// jobs of at most kTilesPerJob, to the tile-job list: "Visibility Raster" runs one workgroup per
// job, so no workgroup walks a big triangle and none searches for its triangle.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#include "../include/visbuffer_triangle.glsl"

layout(local_size_x = 64) in;

const int kSmallPixels = 8;

bool outsideFrustum(vec4 c[3]) {
  // Each plane test holds for every w sign: the triangle's points are convex combinations.
  // (Straight-line: SIMD devices evaluate every plane anyway.)
  bvec4 beyond0 = bvec4(c[0].x > c[0].w, c[0].x < -c[0].w, c[0].y > c[0].w, c[0].y < -c[0].w);
  bvec4 beyond1 = bvec4(c[1].x > c[1].w, c[1].x < -c[1].w, c[1].y > c[1].w, c[1].y < -c[1].w);
  bvec4 beyond2 = bvec4(c[2].x > c[2].w, c[2].x < -c[2].w, c[2].y > c[2].w, c[2].y < -c[2].w);
  bool sides = any(bvec4(uvec4(beyond0) & uvec4(beyond1) & uvec4(beyond2)));
  bool belowDepthRange = c[0].z < 0.0 && c[1].z < 0.0 && c[2].z < 0.0;
  bool aboveDepthRange = c[0].z > c[0].w && c[1].z > c[1].w && c[2].z > c[2].w;
  return sides || belowDepthRange || aboveDepthRange;
}

// The workgroup's cluster (one cluster of one instance). Every invocation loads it itself rather
// than invocation 0 for all behind a barrier: the loads are the same addresses (broadcast), and a
// shader without barriers runs as straight SIMD code on CPU devices (lavapipe runs the invocations
// of a shader with barriers as coroutines, which cost more than the loads).
struct ClusterSetup {
  uint drawIndex;  // the ClusterDraw: the high bits of the pixel ids
  uint flags;      // ClusterDraw::flags
  mat4 modelViewProj;
  uint firstTriangle;
  uint firstVertex;
  uint triangles;
};

ClusterSetup loadCluster(uint clusterSlot) {
  ClusterSetup c;
  c.drawIndex = fgbUintsRead[pc.visible].values[clusterSlot];
  ClusterDraw draw = visDraws[pc.draws].draws[c.drawIndex];
  c.flags = draw.flags;
  c.modelViewProj = modelViewProj(fgbInstances[pc.instances].instances[draw.instance].model);
  c.firstTriangle = visClusters[pc.clusters].clusters[draw.cluster].firstTriangle;
  c.firstVertex = visClusters[pc.clusters].clusters[draw.cluster].firstVertex;
  c.triangles = visClusters[pc.clusters].clusters[draw.cluster].triangleCount;
  return c;
}

void appendLarge(ScreenTriangle t, uint id, bool masked) {
  uint jobs = tileJobsOf(t.pixels);
  uint64_t totals = atomicAdd(visCounters[pc.counters].c.largeTotals, (uint64_t(1) << 40) | uint64_t(jobs));
  uint slot = uint(totals >> 40);
  uint firstJob = uint(totals & 0xffffffffffUL);
  if (slot >= pc.largeCapacity || uint64_t(firstJob) + jobs > pc.tileJobCapacity) {
    atomicAdd(visCounters[pc.counters].c.overflow, 1u);
    slot = kNoLargeTriangle;  // its jobs (those within capacity) are written empty
  } else {
    uvec4 e[4];
    packLargeTriangle(t, id, masked, e);
    for (uint i = 0u; i < 4u; ++i) visUvec4s[pc.largeList].values[4u * slot + i] = e[i];
  }
  // One invocation writes all of the triangle's jobs: a few for most, and a full-screen box at
  // 1920x1080 has 2 025 (8 bytes each), far less than rasterising it.
  uint end = uint(min(uint64_t(firstJob) + jobs, uint64_t(pc.tileJobCapacity)));
  for (uint job = firstJob; job < end; ++job) visUvec2s[pc.tileJobs].values[job] = uvec2(slot, job - firstJob);
}

// Filters one triangle of the workgroup's cluster: drops it, or appends it to the small list or
// (appendLarge) the large one.
void filterTriangle(ClusterSetup c, uint triangle) {
  uint flags = c.flags;
  uvec3 vertices = clusterTriangleVertices(fgbUintsRead[pc.indices].values[c.firstTriangle + triangle], c.firstVertex);
  if (vertices.x == vertices.y || vertices.y == vertices.z || vertices.x == vertices.z) return;
  ScreenTriangle t = setupTriangle(c.modelViewProj, vertices);
  if (t.clip[0].w <= 0.0 && t.clip[1].w <= 0.0 && t.clip[2].w <= 0.0) return;
  if (outsideFrustum(t.clip)) return;
  if (t.pixels.x > t.pixels.z || t.pixels.y > t.pixels.w) return;  // covers no pixel centre
  if (t.projected && t.area == 0) return;
  if ((flags & kClusterSingleSided) != 0u) {
    bool front = framebufferFront(t) != ((flags & kClusterMirrored) != 0u);
    if (!front) return;
  }
  uint id = (c.drawIndex << kClusterTriangleBits) | triangle;
  bool masked = (flags & kClusterAlphaMasked) != 0u;
  ivec2 span = t.pixels.zw - t.pixels.xy + 1;
  if (t.projected && span.x <= kSmallPixels && span.y <= kSmallPixels && packable(t)) {
    uint slot = atomicAdd(visCounters[pc.counters].c.smallTriangles, 1u);
    uvec4 a, b;
    packSmallTriangle(t, id, masked, a, b);
    visUvec4s[pc.smallList].values[2u * slot] = a;
    visUvec4s[pc.smallList].values[2u * slot + 1u] = b;
  } else {
    appendLarge(t, id, masked);
  }
}

// Which invocations share the cluster's triangles. GPUs run a workgroup's subgroups side by side:
// all 64 invocations take two triangles each. CPU devices (lavapipe: 8 lanes of AVX2) run its
// subgroups one after another on one thread (kFlagSerialSubgroups, set by the feature from the
// adapter type), so more subgroups buy no parallelism and each repeats the cluster setup
// (loadCluster: draw, instance, transform product): there the first subgroup takes all the
// triangles and the others leave at once (atrium 640x360 on lavapipe: about 11 of the filter's
// 46 ms were that setup, seven times over). The subgroup size alone cannot tell: GPUs with 8- or
// 16-wide subgroups run them in parallel too.

void main() {
  uint clusterSlot = linearGroup();
  if (clusterSlot >= visCountersRead[pc.args].c.visibleClusters) return;  // uniform in the workgroup
  clusterSlot += visCountersRead[pc.args].c.firstCluster;  // occ: phase-2 clusters follow phase 1's (0 in phase 1)
  bool wholeGroup = (pc.flags & kFlagSerialSubgroups) == 0u;
  if (!wholeGroup && gl_SubgroupID != 0u) return;  // uniform in the subgroup
  uint sharing = wholeGroup ? gl_WorkGroupSize.x : gl_SubgroupSize;
  uint lane = wholeGroup ? gl_LocalInvocationIndex : gl_SubgroupInvocationID;
  loadFrameGlobals();
  ClusterSetup c = loadCluster(clusterSlot);
  for (uint first = 0u; first < c.triangles; first += sharing) {
    uint triangle = first + lane;
    if (triangle < c.triangles) filterTriangle(c, triangle);
  }
}
