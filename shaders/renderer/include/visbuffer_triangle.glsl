// Triangle setup shared by "Triangle Filter", "Visibility Raster" and "Material Shade" (they must
// agree bit for bit on which pixels a triangle covers); their common push block is VisPush
// (renderer/shared/visbuffer.h).
#ifndef FGB_RENDERER_VISBUFFER_TRIANGLE_GLSL
#define FGB_RENDERER_VISBUFFER_TRIANGLE_GLSL

#extension GL_KHR_shader_subgroup_vote : require
#include "visbuffer.glsl"

layout(push_constant) uniform Push { VisPush pc; };

bool reversedZ() { return (pc.flags & kFlagReversedZ) != 0u; }

const float kMinW = 1e-5;        // vertices closer to the eye plane use homogeneous rasterisation
const float kGuardBand = 16384.0;  // pixels: beyond it, fixed point could overflow
const int kSubPixel = 256;       // 8 bits of sub-pixel precision

struct ScreenTriangle {
  vec4 clip[3];
  bool projected;      // every w > kMinW and inside the guard band: integer edge functions
  ivec2 fixedPos[3];   // sub-pixel positions, y down (projected only)
  int64_t area;        // twice the signed area in sub-pixel units (projected only)
  ivec4 pixels;        // covered pixel-centre range x0, y0, x1, y1 (inclusive; empty if x0 > x1)
};

// The frame's view-projection and viewport, loaded once per invocation (loadFrameGlobals()).
mat4 gViewProj;
vec2 gViewport;
void loadFrameGlobals() {
  gViewProj = fgbFrames[pc.frame].frame.viewProj;
  gViewport = fgbFrames[pc.frame].frame.viewport.xy;
}

vec2 viewportSize() { return gViewport; }

// Every visibility-buffer node transforms with the same model-view-projection product, so they
// agree exactly on each triangle's clip positions (forward.vert's two products differ from it
// only in rounding).
mat4 modelViewProj(mat4 model) { return gViewProj * model; }

// Positions come from the cluster vertex stream (`vertex` is a cluster vertex): one 16-byte
// element per vertex, the position's float bits and (w) the vertex in the attribute streams.
vec3 clusterPosition(uint vertex) { return uintBitsToFloat(visUvec4sRead[pc.positions].values[vertex].xyz); }
vec4 clipPosition(mat4 mvp, uint vertex) { return mvp * vec4(clusterPosition(vertex), 1.0); }

// A cluster vertex's vertex in the scene's attribute streams (normals, tangents, UVs).
uint streamVertex(uint clusterVertex) { return visUvec4sRead[pc.positions].values[clusterVertex].w; }
uvec3 streamVertices(uvec3 clusterVertices) {
  return uvec3(streamVertex(clusterVertices.x), streamVertex(clusterVertices.y), streamVertex(clusterVertices.z));
}

// Screen position (pixels, y down as the viewport transform makes it) of a clip-space point.
vec2 toScreen(vec4 c) { return (c.xy / c.w * 0.5 + 0.5) * viewportSize(); }

// Pixel-centre range covered by a screen-space box [lo, hi] (pixels), clamped to the viewport.
ivec4 pixelRange(vec2 lo, vec2 hi) {
  ivec2 size = ivec2(viewportSize());
  ivec2 first = max(ivec2(ceil(lo - 0.5)), ivec2(0));
  ivec2 last = min(ivec2(floor(hi - 0.5)), size - 1);
  return ivec4(first, last);
}

// Box of the part of the triangle in front of the eye plane (w > kMinW): the clipped polygon's
// vertices. Used for triangles the integer path cannot take.
ivec4 clippedPixelRange(vec4 c[3]) {
  vec2 lo = vec2(1e30), hi = vec2(-1e30);
  for (int i = 0; i < 3; ++i) {
    vec4 a = c[i], b = c[(i + 1) % 3];
    if (a.w > kMinW) {
      vec2 s = clamp(toScreen(a), vec2(-kGuardBand), vec2(kGuardBand));
      lo = min(lo, s);
      hi = max(hi, s);
    }
    if ((a.w > kMinW) != (b.w > kMinW)) {
      vec4 cut = mix(a, b, (kMinW - a.w) / (b.w - a.w));
      vec2 s = clamp(toScreen(cut), vec2(-kGuardBand), vec2(kGuardBand));
      lo = min(lo, s);
      hi = max(hi, s);
    }
  }
  return pixelRange(lo, hi);
}

// Straight-line code (no early exit per vertex): SIMD devices evaluate all three vertices anyway.
// A vertex at or behind w = kMinW makes its screen position meaningless, but then the triangle is
// not `projected` and only its clip positions are used. The rare unprojected triangles' clipped
// box sits behind a subgroup vote: SIMD CPU devices (lavapipe) run a divergent branch under a
// mask, a branch uniform in the subgroup only when taken.
ScreenTriangle setupTriangle(mat4 mvp, uvec3 vertices) {
  ScreenTriangle t;
  t.clip[0] = clipPosition(mvp, vertices.x);
  t.clip[1] = clipPosition(mvp, vertices.y);
  t.clip[2] = clipPosition(mvp, vertices.z);
  vec2 s0 = toScreen(t.clip[0]), s1 = toScreen(t.clip[1]), s2 = toScreen(t.clip[2]);
  t.projected = t.clip[0].w > kMinW && t.clip[1].w > kMinW && t.clip[2].w > kMinW &&
                !any(greaterThan(max(abs(s0), max(abs(s1), abs(s2))), vec2(kGuardBand)));
  if (subgroupAny(!t.projected) && !t.projected) {  // see above
    t.area = 0;
    t.pixels = clippedPixelRange(t.clip);
  }
  if (!t.projected) return t;
  t.fixedPos[0] = ivec2(round(s0 * float(kSubPixel)));
  t.fixedPos[1] = ivec2(round(s1 * float(kSubPixel)));
  t.fixedPos[2] = ivec2(round(s2 * float(kSubPixel)));
  vec2 lo = vec2(min(t.fixedPos[0], min(t.fixedPos[1], t.fixedPos[2]))) / float(kSubPixel);
  vec2 hi = vec2(max(t.fixedPos[0], max(t.fixedPos[1], t.fixedPos[2]))) / float(kSubPixel);
  ivec2 e1 = t.fixedPos[1] - t.fixedPos[0], e2 = t.fixedPos[2] - t.fixedPos[0];
  t.area = int64_t(e1.x) * int64_t(e2.y) - int64_t(e1.y) * int64_t(e2.x);
  t.pixels = pixelRange(lo, hi);
  return t;
}

// Vulkan's facing for the default counter-clockwise front face: front when the framebuffer-space
// area -1/2 sum(x_i y_i+1 - x_i+1 y_i) is positive, i.e. our `area` is negative. The homogeneous
// form (Olano and Greer): det(x, y, w) has the sign of the volume of the eye and the triangle,
// i.e. says which side of the triangle's plane the eye is on, whatever the signs of the w. With
// every w positive the projected area is det / (w0 w1 w2), so front is det < 0 there too; a
// triangle with one or three corners behind the eye has w0 w1 w2 < 0, and multiplying by it (as
// this did) called the visible part of a floor that reaches behind the eye back-facing.
bool framebufferFront(ScreenTriangle t) {
  if (t.projected) return t.area < 0;
  mat3 m = mat3(t.clip[0].xyw, t.clip[1].xyw, t.clip[2].xyw);
  return determinant(m) < 0.0;
}

// Integer edge functions with the top-left rule (Vulkan/D3D: a sample on an edge belongs to the
// triangle whose edge is a top or left edge). Vertices are ordered so the area is positive.
struct EdgeSetup {
  ivec2 v[3];
  int64_t area;
  ivec3 bias;  // 0 for top-left edges, -1 otherwise (a sample exactly on the edge is outside)
};

bool isTopLeft(ivec2 a, ivec2 b) {
  ivec2 d = b - a;
  return (d.y == 0 && d.x > 0) || d.y < 0;
}

int64_t edgeFunction(ivec2 a, ivec2 b, ivec2 p) {
  return int64_t(b.x - a.x) * int64_t(p.y - a.y) - int64_t(b.y - a.y) * int64_t(p.x - a.x);
}

EdgeSetup edgeSetupOrdered(ivec2 v0, ivec2 v1, ivec2 v2, int64_t area) {
  EdgeSetup s;
  s.v[0] = v0;
  s.v[1] = v1;
  s.v[2] = v2;
  s.area = area;
  s.bias = ivec3(isTopLeft(v1, v2) ? 0 : -1, isTopLeft(v2, v0) ? 0 : -1, isTopLeft(v0, v1) ? 0 : -1);
  return s;
}

// Screen-space (affine) weights of vertices 0, 1, 2 at a pixel centre (in the triangle's own
// vertex order: `swapped` when edgeSetup exchanged vertices 1 and 2), or a negative x when the
// sample is outside.
vec3 coverage(EdgeSetup s, bool swapped, ivec2 pixel) {
  ivec2 p = pixel * kSubPixel + kSubPixel / 2;
  int64_t w0 = edgeFunction(s.v[1], s.v[2], p) + s.bias.x;
  int64_t w1 = edgeFunction(s.v[2], s.v[0], p) + s.bias.y;
  int64_t w2 = edgeFunction(s.v[0], s.v[1], p) + s.bias.z;
  if (w0 < 0 || w1 < 0 || w2 < 0) return vec3(-1.0);
  vec3 w = vec3(float(w0 - s.bias.x), float(w1 - s.bias.y), float(w2 - s.bias.z)) / float(s.area);
  return swapped ? w.xzy : w;
}
vec3 coverage(EdgeSetup s, ScreenTriangle t, ivec2 pixel) { return coverage(s, !(t.area > 0), pixel); }

EdgeSetup edgeSetup(ScreenTriangle t) {
  bool keep = t.area > 0;
  return edgeSetupOrdered(t.fixedPos[0], keep ? t.fixedPos[1] : t.fixedPos[2], keep ? t.fixedPos[2] : t.fixedPos[1],
                          abs(t.area));
}

// Whether the triangle covers a pixel centre, and its NDC depth there (before depth clipping):
// integer edge functions for a projected triangle (`edges`: edgeSetup(t)), homogeneous ones for
// the others (`frame`: barycentricFrame of its clip positions; unused for projected ones).
bool coveredDepth(ScreenTriangle t, EdgeSetup edges, BarycentricFrame frame, ivec2 pixel, out float z) {
  z = 0.0;
  if (t.projected) {
    vec3 w = coverage(edges, t, pixel);
    if (w.x < 0.0) return false;
    vec3 ndcZ = vec3(t.clip[0].z / t.clip[0].w, t.clip[1].z / t.clip[1].w, t.clip[2].z / t.clip[2].w);
    z = dot(w, ndcZ);
    return true;
  }
  vec3 e = frame.inverse * vec3(pixelNdc(uvec2(pixel), viewportSize()), 1.0);
  if (e.x < 0.0 || e.y < 0.0 || e.z < 0.0 || e.x + e.y + e.z <= 0.0) return false;
  z = dot(e, vec3(t.clip[0].z, t.clip[1].z, t.clip[2].z));
  return true;
}

// Small triangles travel from "Triangle Filter" to "Visibility Raster" already set up (two uvec4
// per triangle), so the raster fetches nothing else: the id, the first covered pixel, the three
// sub-pixel positions relative to that pixel (16 bits each) and the three NDC depths.
uint packOffset(ivec2 offset) { return uint(offset.x & 0xffff) | (uint(offset.y) << 16); }
ivec2 unpackOffset(uint packed) { return ivec2(int(packed << 16) >> 16, int(packed) >> 16); }

// The packed offsets must stay within 16 sub-pixel pixels of the first pixel so 16 bits hold them
// and 32-bit edge functions cannot overflow (a triangle clipped by the viewport edge can cover few
// pixels yet reach far beyond them: it takes the tile path).
bool packable(ScreenTriangle t) {
  ivec2 origin = t.pixels.xy * kSubPixel;
  ivec2 reach = max(abs(t.fixedPos[0] - origin), max(abs(t.fixedPos[1] - origin), abs(t.fixedPos[2] - origin)));
  return !any(greaterThan(reach, ivec2(16 * kSubPixel)));
}

const uint kSmallMasked = 0x80000000u;  // in a.y: alpha-masked (the raster loads its material)

void packSmallTriangle(ScreenTriangle t, uint id, bool masked, out uvec4 a, out uvec4 b) {
  ivec2 origin = t.pixels.xy * kSubPixel;
  a = uvec4(id, uint(t.pixels.x) | (uint(t.pixels.y) << 16) | (masked ? kSmallMasked : 0u), packOffset(t.fixedPos[0] - origin),
            packOffset(t.fixedPos[1] - origin));
  b = uvec4(packOffset(t.fixedPos[2] - origin), floatBitsToUint(t.clip[0].z / t.clip[0].w),
            floatBitsToUint(t.clip[1].z / t.clip[1].w), floatBitsToUint(t.clip[2].z / t.clip[2].w));
}

// The large-triangle path's tile jobs. (VisCounters::largeTotals' low 40 bits and tileJobs count
// these jobs, not single tiles, and tileGroups dispatches one workgroup per job.)
const uint kTilesPerJob = 16u;              // 8x8 tiles of one triangle per job, at most
const uint kNoLargeTriangle = 0xffffffffu;  // a job whose triangle did not fit the large list
FGB_STORAGE_BUFFER(Uvec2Block, visUvec2s, ) { uvec2 values[]; } visUvec2s[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(Uvec2ReadBlock, visUvec2sRead) { uvec2 values[]; } visUvec2sRead[FGB_MAX_STORAGE_BUFFERS];

// Large triangles travel set up too (4 uvec4 per triangle): "Visibility Raster" runs jobs of at
// most kTilesPerJob 8x8 tiles of one triangle, and each job reads its triangle from here instead
// of rebuilding it. Triangles that are alpha-masked or not `projected` (eye plane, guard band) are
// flagged: those jobs rebuild the triangle (loadTriangle) for the per-pixel alpha test or the
// homogeneous edge functions.
const uint kLargeMasked = 1u;
const uint kLargeHomogeneous = 2u;  // not projected: the fixed-point fields are unused
const uint kLargeSwapped = 4u;      // edgeSetup exchanged vertices 1 and 2 (negative area)

struct LargeTriangle {
  uint id;
  uint flags;
  ivec4 pixels;  // covered pixel-centre range x0, y0, x1, y1 (inclusive)
  EdgeSetup edges;
  vec3 ndcZ;     // NDC depth of vertices 0, 1, 2 in the triangle's own order
};

uint packPixel(ivec2 pixel) { return uint(pixel.x) | (uint(pixel.y) << 16); }
ivec2 unpackPixel(uint packed) { return ivec2(packed & 0xffffu, packed >> 16); }

void packLargeTriangle(ScreenTriangle t, uint id, bool masked, out uvec4 e[4]) {
  uint flags = (masked ? kLargeMasked : 0u) | (t.projected ? 0u : kLargeHomogeneous) | (t.area > 0 ? 0u : kLargeSwapped);
  e[0] = uvec4(id, flags, packPixel(t.pixels.xy), packPixel(t.pixels.zw));
  e[1] = uvec4(0u);
  e[2] = uvec4(0u);
  e[3] = uvec4(0u);
  if (!t.projected) return;
  EdgeSetup s = edgeSetup(t);
  e[1] = uvec4(uint(s.area), uint(s.area >> 32), uvec2(s.v[0]));
  e[2] = uvec4(uvec2(s.v[1]), uvec2(s.v[2]));
  e[3] = uvec4(floatBitsToUint(t.clip[0].z / t.clip[0].w), floatBitsToUint(t.clip[1].z / t.clip[1].w),
               floatBitsToUint(t.clip[2].z / t.clip[2].w), 0u);
}

LargeTriangle unpackLargeTriangle(uvec4 e[4]) {
  LargeTriangle l;
  l.id = e[0].x;
  l.flags = e[0].y;
  l.pixels = ivec4(unpackPixel(e[0].z), unpackPixel(e[0].w));
  int64_t area = int64_t(uint64_t(e[1].x) | (uint64_t(e[1].y) << 32));
  l.edges = edgeSetupOrdered(ivec2(e[1].zw), ivec2(e[2].xy), ivec2(e[2].zw), area);
  l.ndcZ = uintBitsToFloat(e[3].xyz);
  return l;
}

// The 8x8 tiles of the triangle's pixel range, and how many jobs cover them.
uvec2 firstTileOf(ivec4 pixels) { return uvec2(pixels.xy) / kTileSize; }
uvec2 tileCountsOf(ivec4 pixels) { return uvec2(pixels.zw) / kTileSize - firstTileOf(pixels) + 1u; }
uint tileJobsOf(ivec4 pixels) {
  uvec2 tiles = tileCountsOf(pixels);
  return (tiles.x * tiles.y + kTilesPerJob - 1u) / kTilesPerJob;
}

#endif
