#version 460
// "Visibility Raster": writes (depth key << 32 | id) into the visibility buffer with a 64-bit
// atomic max per covered pixel centre (storage buffer, or R64 image in the "image" variant). Two
// dispatches of this shader in one node: small triangles (one invocation each walks its at most
// 8x8 pixel centres) and the tile jobs of large triangles (one workgroup per job of up to
// kTilesPerJob 8x8-pixel tiles, one invocation per pixel of each tile). Projected triangles use
// 8-bit sub-pixel integer edge functions with the top-left rule; those crossing the eye plane or
// the guard band use homogeneous edge functions. Depth outside [0, 1] is clipped per pixel, like
// the hardware's depth clipping, and alpha-masked materials are tested per pixel.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#include "../include/visbuffer_material.glsl"

layout(local_size_x = FGB_VIS_RASTER_GROUP_SIZE) in;

// What the alpha test needs of a triangle.
struct AlphaTest {
  BarycentricFrame frame;
  uvec3 vertices;
  Material material;
};

struct RasterTriangle {
  ScreenTriangle screen;
  EdgeSetup edges;
  BarycentricFrame frame;  // homogeneous path and alpha test
  uvec3 vertices;
  bool masked;
  Material material;
  uint id;
};

RasterTriangle loadTriangle(uint id) {
  RasterTriangle r;
  r.id = id;
  uint drawIndex = id >> kClusterTriangleBits;
  VisTriangle tri = visTriangle(drawIndex, id & ((1u << kClusterTriangleBits) - 1u), pc.draws, pc.clusters, pc.indices);
  r.vertices = tri.vertices;
  r.screen = setupTriangle(modelViewProj(fgbInstances[pc.instances].instances[tri.instance].model), tri.vertices);
  if (r.screen.projected) r.edges = edgeSetup(r.screen);
  r.masked = (tri.flags & kClusterAlphaMasked) != 0u;
  if (r.masked)
    r.material = fgbMaterials[pc.materials].materials[fgbInstances[pc.instances].instances[tri.instance].material];
  if (r.masked || !r.screen.projected)
    r.frame = barycentricFrame(r.screen.clip[0], r.screen.clip[1], r.screen.clip[2], viewportSize());
  return r;
}

// The alpha test's inputs alone, for a small triangle whose coverage came packed: the same clip
// positions as loadTriangle's (same product, same fetches), without the screen and edge setup.
AlphaTest loadAlphaTest(uint id) {
  uint drawIndex = id >> kClusterTriangleBits;
  VisTriangle tri = visTriangle(drawIndex, id & ((1u << kClusterTriangleBits) - 1u), pc.draws, pc.clusters, pc.indices);
  mat4 mvp = modelViewProj(fgbInstances[pc.instances].instances[tri.instance].model);
  AlphaTest t;
  t.vertices = tri.vertices;
  t.material = fgbMaterials[pc.materials].materials[fgbInstances[pc.instances].instances[tri.instance].material];
  t.frame = barycentricFrame(clipPosition(mvp, tri.vertices.x), clipPosition(mvp, tri.vertices.y),
                             clipPosition(mvp, tri.vertices.z), viewportSize());
  return t;
}

bool alphaPasses(AlphaTest t, ivec2 pixel) {
  vec3 b, dbdx, dbdy;
  barycentricsAt(t.frame, pixelNdc(uvec2(pixel), viewportSize()), b, dbdx, dbdy);
  vec2 uv = interpolateUv(t.vertices, b, dbdx, dbdy);
  return surfaceBaseColor(t.material, uv).a >= t.material.alphaCutoff;
}
bool alphaPasses(RasterTriangle r, ivec2 pixel) {
  return alphaPasses(AlphaTest(r.frame, r.vertices, r.material), pixel);
}

// The alpha test (up to kMaxAnisotropy texture taps) is skipped where the word cannot win the
// max: a pixel's words only grow during the pass, so a depth key already greater than ours (in a
// stale read too) keeps ours out whatever the test says. Only the key half is compared, strictly:
// a plain 64-bit read racing the atomics could pair halves of two words, a 32-bit half cannot be
// torn. Leaves behind leaves and walls are common.
bool keyBeaten(ivec2 pixel, uint width, uint key) { return uint(visWordAt(pc.words, pixel, width) >> 32) > key; }

void rasterPixel(RasterTriangle r, ivec2 pixel) {
  float z;
  if (!coveredDepth(r.screen, r.edges, r.frame, pixel, z)) return;
  if (!(z >= 0.0 && z <= 1.0)) return;  // depth clipping (also drops NaN)
  uint width = uint(viewportSize().x);
  uint key = depthKey(z, reversedZ());
  if (r.masked && (keyBeaten(pixel, width, key) || !alphaPasses(r, pixel))) return;  // keyBeaten: see there
  uint64_t word = (uint64_t(key) << 32) | uint64_t(r.id);
  visWordMax(pc.words, pixel, width, word);
}

int edge32(ivec2 a, ivec2 b, ivec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// A small triangle as "Triangle Filter" packed it (packSmallTriangle): positions relative to its
// first covered pixel fit 32-bit edge functions. Same coverage rule as coverage(): top-left, pixel
// centres, and the same pixel range (pixelRange of the vertex box). The box is walked from
// pixels.xy in rows with the edge functions stepped by their exact integer increments (the same
// values as evaluating them at each pixel centre).
struct SmallTriangle {
  uint id;
  ivec4 pixels;
  int area;            // positive: vertices 1 and 2 exchanged where the packed order had it negative
  bool swapped;        // so exchanged
  vec3 ndcZ;           // NDC depths in the packed order
  ivec3 minW;          // a pixel centre is covered when every edge function w >= minW (0 on top-left edges)
  ivec3 rowStart;      // edge functions at the centre of pixels.xy
  ivec3 stepX, stepY;  // and their increments per pixel
};

SmallTriangle unpackSmallTriangle(uvec4 a, uvec4 b) {
  SmallTriangle t;
  t.id = a.x;
  ivec2 first = ivec2(a.y & 0xffffu, (a.y >> 16) & 0x7fffu);
  ivec2 v[3] = ivec2[3](unpackOffset(a.z), unpackOffset(a.w), unpackOffset(b.x));
  t.ndcZ = vec3(uintBitsToFloat(b.y), uintBitsToFloat(b.z), uintBitsToFloat(b.w));
  t.area = edge32(v[0], v[1], v[2]);
  t.swapped = t.area < 0;
  if (t.swapped) {
    ivec2 swap = v[1];
    v[1] = v[2];
    v[2] = swap;
    t.area = -t.area;
  }
  t.minW = ivec3(isTopLeft(v[1], v[2]) ? 0 : 1, isTopLeft(v[2], v[0]) ? 0 : 1, isTopLeft(v[0], v[1]) ? 0 : 1);
  ivec2 origin = first * kSubPixel;
  vec2 lo = vec2(origin + min(v[0], min(v[1], v[2]))) / float(kSubPixel);
  vec2 hi = vec2(origin + max(v[0], max(v[1], v[2]))) / float(kSubPixel);
  t.pixels = pixelRange(lo, hi);
  // edge32(a, b, p) grows by (a.y - b.y) * kSubPixel per pixel in x and (b.x - a.x) * kSubPixel in y.
  t.stepX = ivec3(v[1].y - v[2].y, v[2].y - v[0].y, v[0].y - v[1].y) * kSubPixel;
  t.stepY = ivec3(v[2].x - v[1].x, v[0].x - v[2].x, v[1].x - v[0].x) * kSubPixel;
  ivec2 p = (t.pixels.xy - first) * kSubPixel + kSubPixel / 2;
  t.rowStart = ivec3(edge32(v[1], v[2], p), edge32(v[2], v[0], p), edge32(v[0], v[1], p));
  return t;
}

int pixelCount(SmallTriangle t) {
  ivec2 span = max(t.pixels.zw - t.pixels.xy + 1, ivec2(0));
  return span.x * span.y;
}

// To the next pixel of the box, row by row. Selects, not branches: every lane steps alike.
void stepPixel(SmallTriangle t, inout ivec2 pixel, inout ivec3 rowStart, inout ivec3 w) {
  bool rowEnd = pixel.x == t.pixels.z;
  rowStart += rowEnd ? t.stepY : ivec3(0);
  w = rowEnd ? rowStart : w + t.stepX;
  pixel = rowEnd ? ivec2(t.pixels.x, pixel.y + 1) : ivec2(pixel.x + 1, pixel.y);
}

// Depth of an alpha-masked triangle at edge functions w: coverage()'s weights (divided by the
// area, in the packed vertex order), as loadTriangle's path computed it before.
float maskedDepth(SmallTriangle t, ivec3 w) {
  vec3 weights = vec3(w) / float(t.area);
  return dot(t.swapped ? weights.xzy : weights, t.ndcZ);
}

// The pixels of an alpha-masked small triangle's box (row-major indices, at most 8x8 = 64: one
// bit each in a uint64_t) that need the alpha test: covered, in depth and not already beaten
// (keyBeaten). Most leaves (hidden or covering no pixel centre) have none.
uint64_t maskedCandidates(SmallTriangle t) {
  uint width = uint(viewportSize().x);
  int count = pixelCount(t);
  ivec3 rowStart = t.rowStart, w = rowStart;
  ivec2 pixel = t.pixels.xy;
  uint64_t candidates = 0ul;
  for (int i = 0; i < count; ++i) {
    if (all(greaterThanEqual(w, t.minW))) {
      float z = maskedDepth(t, w);
      if (z >= 0.0 && z <= 1.0 && !keyBeaten(pixel, width, depthKey(z, reversedZ())))  // depth clipping (also NaN)
        candidates |= 1ul << uint(i);
    }
    stepPixel(t, pixel, rowStart, w);
  }
  return candidates;
}

// Alpha tests and writes the candidate pixels, one per iteration for every lane (not one per box
// pixel): SIMD CPU devices then sample the textures with every lane that has work left.
void rasterMaskedCandidates(SmallTriangle t, uint64_t candidates) {
  AlphaTest alpha = loadAlphaTest(t.id);
  uint width = uint(viewportSize().x);
  int spanX = t.pixels.z - t.pixels.x + 1;
  while (candidates != 0ul) {
    uint low = uint(candidates), high = uint(candidates >> 32);
    int i = low != 0u ? findLSB(low) : 32 + findLSB(high);
    candidates &= candidates - 1ul;
    ivec2 offset = ivec2(i % spanX, i / spanX);
    ivec3 w = t.rowStart + offset.x * t.stepX + offset.y * t.stepY;  // what stepPixel reaches
    ivec2 pixel = t.pixels.xy + offset;
    uint key = depthKey(maskedDepth(t, w), reversedZ());
    if (!keyBeaten(pixel, width, key) && alphaPasses(alpha, pixel))
      visWordMax(pc.words, pixel, width, (uint64_t(key) << 32) | uint64_t(t.id));
  }
}

void rasterSmallMasked(SmallTriangle t) {
  uint64_t candidates = maskedCandidates(t);
  bool needed = candidates != 0ul;
  if (subgroupAny(needed) && needed) rasterMaskedCandidates(t, candidates);  // see rasterSmall
}

// One invocation per small triangle. SIMD CPU devices (lavapipe) run a loop as long as its longest
// lane and a divergent branch under a mask whether or not any lane takes it, so: the masked path
// sits behind a subgroup vote, and the box is one flat loop (a lane with a 1x8 box and one with an
// 8x1 box cost 8 iterations, not 64).
void rasterSmall() {
  uint slot = linearGroup() * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (slot >= visCountersRead[pc.args].c.smallTriangles) return;
  uvec4 a = visUvec4sRead[pc.smallList].values[2u * slot];
  uvec4 b = visUvec4sRead[pc.smallList].values[2u * slot + 1u];
  SmallTriangle t = unpackSmallTriangle(a, b);
  bool masked = (a.y & kSmallMasked) != 0u;
  if (subgroupAny(masked) && masked) {  // see above
    rasterSmallMasked(t);
    return;
  }
  int count = pixelCount(t);
  float invArea = 1.0 / float(t.area);
  vec3 ndcZ = t.swapped ? t.ndcZ.xzy : t.ndcZ;  // in the exchanged vertex order, like w
  uint64_t id = uint64_t(t.id);
  uint width = uint(viewportSize().x);
  ivec3 rowStart = t.rowStart, w = rowStart;
  ivec2 pixel = t.pixels.xy;
  for (int i = 0; i < count; ++i) {
    if (all(greaterThanEqual(w, t.minW))) {
      float z = dot(vec3(w) * invArea, ndcZ);
      if (z >= 0.0 && z <= 1.0)  // depth clipping (also drops NaN)
        visWordMax(pc.words, pixel, width, (uint64_t(depthKey(z, reversedZ())) << 32) | id);
    }
    stepPixel(t, pixel, rowStart, w);
  }
}

// One workgroup per tile job, one invocation per pixel of each of its tiles. Every invocation
// reads the job's triangle itself (same addresses: broadcast loads) instead of invocation 0 for
// all behind a barrier: without barriers the shader runs as straight SIMD code on CPU devices
// (lavapipe runs a shader with barriers as coroutines). Triangles flagged masked or homogeneous are
// rebuilt (loadTriangle: the alpha test needs vertices and material, the homogeneous edge
// functions the clip positions); the others come set up from the large list.
void rasterTileJob() {
  uint jobIndex = linearGroup();
  if (jobIndex >= visCountersRead[pc.args].c.tileJobs) return;  // uniform across the workgroup
  uvec2 job = visUvec2sRead[pc.tileJobs].values[jobIndex];
  if (job.x == kNoLargeTriangle) return;  // the large list overflowed (counted)
  uvec4 e[4];
  for (uint i = 0u; i < 4u; ++i) e[i] = visUvec4sRead[pc.largeList].values[4u * job.x + i];
  LargeTriangle l = unpackLargeTriangle(e);
  bool general = (l.flags & (kLargeMasked | kLargeHomogeneous)) != 0u;
  RasterTriangle r;
  if (general) r = loadTriangle(l.id);
  uvec2 firstTile = firstTileOf(l.pixels), tiles = tileCountsOf(l.pixels);
  uint firstLocal = job.y * kTilesPerJob, endLocal = min(firstLocal + kTilesPerJob, tiles.x * tiles.y);
  ivec2 inTile = ivec2(gl_LocalInvocationID.x % kTileSize, gl_LocalInvocationID.x / kTileSize);
  uint64_t id = uint64_t(l.id);
  uint width = uint(viewportSize().x);
  bool swapped = (l.flags & kLargeSwapped) != 0u;
  for (uint local = firstLocal; local < endLocal; ++local) {
    ivec2 pixel = ivec2((firstTile + uvec2(local % tiles.x, local / tiles.x)) * kTileSize) + inTile;
    if (any(lessThan(pixel, l.pixels.xy)) || any(greaterThan(pixel, l.pixels.zw))) continue;
    if (general) {
      rasterPixel(r, pixel);
      continue;
    }
    vec3 w = coverage(l.edges, swapped, pixel);
    if (w.x < 0.0) continue;
    float z = dot(w, l.ndcZ);
    if (!(z >= 0.0 && z <= 1.0)) continue;  // depth clipping (also drops NaN)
    visWordMax(pc.words, pixel, width, (uint64_t(depthKey(z, reversedZ())) << 32) | id);
  }
}

void main() {
  loadFrameGlobals();
  if ((pc.flags & kFlagLargeTiles) != 0u) rasterTileJob();
  else rasterSmall();
}
