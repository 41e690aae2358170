#version 460
// "Transparent Raster" (render.transparent=compute): offers every transparent fragment in front of
// the opaque depth to its pixel's K-buffer (include/transparent_compute.glsl), keeping the K
// nearest sorted: the atomicMin cascade, each slot keeping the smaller word and passing the larger
// on (old = atomicMin(slot[i], v), v = max(old, v), until old is kEmpty); what passes the last
// slot is dropped (counted).
// Concurrent insertions commute: each step swaps within the multiset of words, so the slots end
// holding the K smallest in order whatever order they arrive in. Coverage is the visibility
// buffer's (visbuffer_triangle.glsl: setupTriangle, coveredDepth: 8-bit sub-pixel integer edge
// functions, top-left rule, pixel centres, homogeneous edge functions behind the eye, depth
// clipping), the depth test the raster pass's (include/opaque_depth.glsl).
// Two dispatches in one node: one workgroup per packed cluster draw (indirect: the count
// "Transparent Cluster Cull" kept), one invocation per triangle,
// which walks a small triangle's box itself and appends a large one (more than
// FGB_TRANSPARENT_SMALL_PIXELS pixels in its box) to the large list; then (kFlagLargeTiles)
// FGB_TRANSPARENT_LARGE_GROUPS workgroups walk that list, each sharing one triangle's pixels among
// its invocations. No barriers: lavapipe runs a shader with barriers as coroutines.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#include "../include/transparent_compute.glsl"
#include "../include/opaque_depth.glsl"

layout(local_size_x = FGB_TRANSPARENT_RASTER_GROUP_SIZE) in;

FGB_STORAGE_BUFFER(TransparentCounterBlock, transparentCounters, ) { TransparentCounters c; } transparentCounters[FGB_MAX_STORAGE_BUFFERS];

struct TransparentTriangle {
  ScreenTriangle screen;
  EdgeSetup edges;         // projected triangles
  BarycentricFrame frame;  // the others (homogeneous edge functions)
  uint id;
};

TransparentTriangle loadTriangle(uint id) {
  VisTriangle tri = transparentTriangle(id);
  TransparentTriangle t;
  t.id = id;
  t.screen = setupTriangle(modelViewProj(fgbInstances[pc.instances].instances[tri.instance].model), tri.vertices);
  if (tri.vertices.x == tri.vertices.y || tri.vertices.y == tri.vertices.z || tri.vertices.x == tri.vertices.z ||
      (t.screen.projected && t.screen.area == 0))
    t.screen.pixels = ivec4(0, 0, -1, -1);  // degenerate: covers nothing
  if (t.screen.projected)
    t.edges = edgeSetup(t.screen);
  else
    t.frame = barycentricFrame(t.screen.clip[0], t.screen.clip[1], t.screen.clip[2], viewportSize());
  return t;
}

ivec2 boxSize(TransparentTriangle t) { return max(t.screen.pixels.zw - t.screen.pixels.xy + 1, ivec2(0)); }

// This invocation's fragments offered and dropped, added to the counters once per subgroup.
uint gInserted = 0u;
uint gDropped = 0u;

// Lists the pixel's tile for "Transparent Shade" if no fragment did this frame: the invocation
// whose exchange finds the flag empty appends it and raises the shade's dispatch to cover it.
// The plain load skips the atomic once the tile is listed (flags only go from kEmpty to 0 here:
// a stale kEmpty costs one exchange, never a second listing); gMarkedTile skips the load too
// while an invocation's fragments stay in one tile, as a small triangle's mostly do.
uint gMarkedTile = 0xffffffffu;

void markTile(uvec2 pixel) {
  uint tile = (pixel.y / FGB_TRANSPARENT_SHADE_GROUP_SIZE) * tilesAcross() + pixel.x / FGB_TRANSPARENT_SHADE_GROUP_SIZE;
  if (tile == gMarkedTile) return;
  gMarkedTile = tile;
  uint flag = tileFlagIndex(tile);
  if (visWords[pc.words].words[flag] != kEmpty) return;
  if (atomicExchange(visWords[pc.words].words[flag], 0UL) != kEmpty) return;
  uint slot = atomicAdd(fgbUints[pc.tileJobs].values[0], 1u);
  fgbUints[pc.tileJobs].values[1u + slot] = tile;
  atomicAdd(transparentCounters[pc.counters].c.tilesListed, 1u);
  const uint row = FGB_TRANSPARENT_SHADE_GROUPS_X;
  if (slot < row) atomicMax(transparentCounters[pc.counters].c.shadeGroupsX, slot + 1u);
  if (slot % row == 0u) atomicMax(transparentCounters[pc.counters].c.shadeGroupsY, slot / row + 1u);
}

void insertFragment(uvec2 pixel, uint64_t word) {
  markTile(pixel);
  uint pixelIndex = pixel.y * uint(viewportSize().x) + pixel.x;
  ++gInserted;
  for (uint i = 0u; i < TRANSPARENT_K; ++i) {
    uint64_t previous = atomicMin(visWords[pc.words].words[kSlotIndex(i, pixelIndex)], word);
    if (previous == kEmpty) return;
    word = max(previous, word);  // the slot kept the smaller: the larger goes on
  }
  ++gDropped;  // the farthest of the K + 1 fell off the end
}

void rasterPixel(TransparentTriangle t, ivec2 pixel) {
  float z;
  if (!coveredDepth(t.screen, t.edges, t.frame, pixel, z)) return;
  if (!(z >= 0.0 && z <= 1.0)) return;  // depth clipping (also drops NaN)
  OpaqueDepthTest opaque = OpaqueDepthTest(pc.depthOut, uint(viewportSize().x), pc.depthCompare);
  if (!passesOpaqueDepth(opaque, vec4(vec2(pixel) + 0.5, z, 1.0))) return;
  insertFragment(uvec2(pixel), fragmentWord(z, t.id));
}

// The pixels of the box from `first`, `stride` apart (row-major).
void rasterBox(TransparentTriangle t, uint first, uint stride) {
  ivec2 size = boxSize(t);
  uint pixels = uint(size.x * size.y);
  for (uint i = first; i < pixels; i += stride)
    rasterPixel(t, t.screen.pixels.xy + ivec2(int(i % uint(size.x)), int(i / uint(size.x))));
}

void rasterSmall() {
  uint draw = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;  // the pack's (x, y) dispatch
  uint triangle = gl_LocalInvocationID.x;
  if (draw >= fgbUintsRead[pc.args].values[0]) return;  // uniform across the workgroup
  if (triangle >= transparentDraws[pc.draws].draws[draw].indexCount / 3u) return;
  TransparentTriangle t = loadTriangle((draw << kClusterTriangleBits) | triangle);
  ivec2 size = boxSize(t);
  if (size.x * size.y > FGB_TRANSPARENT_SMALL_PIXELS) {
    uint slot = atomicAdd(transparentCounters[pc.counters].c.largeTriangles, 1u);
    if (slot < pc.largeCapacity) {
      fgbUints[pc.largeList].values[slot] = t.id;
      return;
    }
    atomicAdd(transparentCounters[pc.counters].c.largeOverflow, 1u);  // rasterised here instead
  }
  rasterBox(t, 0u, 1u);
}

void rasterLarge() {
  uint count = min(transparentCounters[pc.counters].c.largeTriangles, pc.largeCapacity);
  for (uint slot = gl_WorkGroupID.x; slot < count; slot += gl_NumWorkGroups.x)
    rasterBox(loadTriangle(fgbUints[pc.largeList].values[slot]), gl_LocalInvocationID.x, gl_WorkGroupSize.x);
}

void main() {
  loadFrameGlobals();
  if ((pc.flags & kFlagLargeTiles) != 0u)
    rasterLarge();
  else
    rasterSmall();
  uint inserted = subgroupAdd(gInserted), dropped = subgroupAdd(gDropped);
  if (subgroupElect() && inserted > 0u) {
    atomicAdd(transparentCounters[pc.counters].c.inserted, inserted);
    atomicAdd(transparentCounters[pc.counters].c.dropped, dropped);
  }
}
