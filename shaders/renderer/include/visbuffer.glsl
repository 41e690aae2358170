// Shared by the visibility-buffer shaders (shaders/renderer/visbuffer/*.comp). Their structs, push
// blocks and flags are declared once for C++ and GLSL in renderer/shared/visbuffer.h.
//
// The visibility buffer holds one 64-bit word per pixel: a depth key in the high 32 bits and the
// pixel's id in the low 32 bits, written with a 64-bit atomic max. Its backing
// (render.vis_backing) is a storage buffer of row-major words, or, in the shader variants compiled
// with FGB_VIS_BACKING_IMAGE (shaders/CMakeLists.txt), an R64_UINT storage image with 64-bit image
// atomics; shaders reach it only through visWordMax and visWordAt. The depth key grows towards the
// camera (standard Z: ~bits(z); reversed Z: bits(z)), so max keeps the nearest triangle and the
// cleared value 0 means "nothing". The id is (cluster draw << 7) | triangle in the cluster: the
// ClusterDraw index, not the cluster's slot in the visible list, so a depth tie between triangles
// (e.g. where a simplified LOD cluster folds over itself) is won by the same triangle whatever
// order the culling appended clusters in (render.occlusion's two phases, atomics' order).
#ifndef FGB_RENDERER_VISBUFFER_GLSL
#define FGB_RENDERER_VISBUFFER_GLSL

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "clusters.glsl"

const uint kClusterTriangleBits = 7u;  // 128 triangles per cluster
const uint kTileSize = 8u;             // large triangles are rasterised in 8x8-pixel tiles
const uint kDispatchWidth = 32768u;    // indirect dispatches are (min(n, W), ceil(n / W)) groups

FGB_STORAGE_BUFFER(VisCounterBlock, visCounters, ) { VisCounters c; } visCounters[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(VisCounterReadBlock, visCountersRead) { VisCounters c; } visCountersRead[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(VisWordBlock, visWords, ) { uint64_t words[]; } visWords[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(VisWordReadBlock, visWordsRead) { uint64_t words[]; } visWordsRead[FGB_MAX_STORAGE_BUFFERS];
#ifdef FGB_VIS_BACKING_IMAGE
#extension GL_EXT_shader_image_int64 : require
layout(set = 0, binding = FGB_BINDING_INT64_STORAGE_TEXTURES, r64ui) uniform u64image2D visImages[FGB_MAX_INT64_STORAGE_TEXTURES];
#endif
FGB_READONLY_STORAGE_BUFFER(FloatReadBlock, visFloatsRead) { float values[]; } visFloatsRead[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(FloatBlock, visFloats, ) { float values[]; } visFloats[FGB_MAX_STORAGE_BUFFERS];
FGB_STORAGE_BUFFER(Uvec4Block, visUvec4s, ) { uvec4 values[]; } visUvec4s[FGB_MAX_STORAGE_BUFFERS];

// The visibility buffer `words` (a storage-buffer index, or with the image backing a storage-texture
// index) at a pixel of a viewport `width` pixels wide: atomic max, and plain read.
void visWordMax(uint words, ivec2 pixel, uint width, uint64_t word) {
#ifdef FGB_VIS_BACKING_IMAGE
  imageAtomicMax(visImages[words], pixel, word);
#else
  atomicMax(visWords[words].words[uint(pixel.y) * width + uint(pixel.x)], word);
#endif
}
// A pixel's word for its last reader ("Material Shade"), which leaves the pixel empty: the
// visibility buffer stays cleared between frames. Empty pixels are not written again.
uint64_t visWordTake(uint words, ivec2 pixel, uint width) {
#ifdef FGB_VIS_BACKING_IMAGE
  uint64_t word = imageLoad(visImages[words], pixel).x;
  if (word != 0ul) imageStore(visImages[words], pixel, u64vec4(0ul));
#else
  uint index = uint(pixel.y) * width + uint(pixel.x);
  uint64_t word = visWords[words].words[index];
  if (word != 0ul) visWords[words].words[index] = 0ul;
#endif
  return word;
}
uint64_t visWordAt(uint words, ivec2 pixel, uint width) {
#ifdef FGB_VIS_BACKING_IMAGE
  return imageLoad(visImages[words], pixel).x;
#else
  return visWordsRead[words].words[uint(pixel.y) * width + uint(pixel.x)];
#endif
}

// Groups for n items of `perGroup` each, laid out as (x, y, 1) within the dispatch limits.
uvec3 dispatchFor(uint items, uint perGroup) {
  uint groups = (items + perGroup - 1u) / perGroup;
  return uvec3(min(groups, kDispatchWidth), (groups + kDispatchWidth - 1u) / kDispatchWidth, 1u);
}
uint linearGroup() { return gl_WorkGroupID.y * kDispatchWidth + gl_WorkGroupID.x; }

// The triangle behind a visibility id: its instance and three cluster vertices (indices into the
// cluster vertex stream, which also gives their vertices in the scene's attribute streams).
struct VisTriangle {
  uint instance;
  uint flags;
  uvec3 vertices;
};

VisTriangle visTriangle(uint drawIndex, uint triangle, uint drawsBuffer, uint clustersBuffer, uint trianglesBuffer) {
  ClusterDraw draw = visDraws[drawsBuffer].draws[drawIndex];
  ClusterData cluster = visClusters[clustersBuffer].clusters[draw.cluster];
  VisTriangle t;
  t.instance = draw.instance;
  t.flags = draw.flags;
  t.vertices =
      clusterTriangleVertices(fgbUintsRead[trianglesBuffer].values[cluster.firstTriangle + triangle], cluster.firstVertex);
  return t;
}

// Perspective-correct barycentrics of a triangle from its clip-space x, y, w (homogeneous
// rasterisation, Olano & Greer 1997): with M = (x; y; w) per vertex as columns, e = M^-1 (ndc, 1)
// is proportional to the barycentrics. Works for any vertex w (no near-plane clipping needed) and
// gives exact screen-space derivatives, so the w ~ 0 breakdown of the usual formula never occurs.
struct BarycentricFrame {
  mat3 inverse;  // M^-1: rows are the edge functions in NDC
  vec2 ndcPerPixel;  // NDC step of one pixel in x and y
};

BarycentricFrame barycentricFrame(vec4 c0, vec4 c1, vec4 c2, vec2 viewportSize) {
  mat3 m = mat3(vec3(c0.x, c0.y, c0.w), vec3(c1.x, c1.y, c1.w), vec3(c2.x, c2.y, c2.w));
  return BarycentricFrame(inverse(m), 2.0 / viewportSize);
}

// Barycentrics at an NDC point and their derivatives per pixel in x and y.
void barycentricsAt(BarycentricFrame f, vec2 ndc, out vec3 b, out vec3 dbdx, out vec3 dbdy) {
  vec3 e = f.inverse * vec3(ndc, 1.0);
  vec3 dedx = f.inverse[0] * f.ndcPerPixel.x;
  vec3 dedy = f.inverse[1] * f.ndcPerPixel.y;
  float s = e.x + e.y + e.z;
  float dsdx = dedx.x + dedx.y + dedx.z;
  float dsdy = dedy.x + dedy.y + dedy.z;
  b = e / s;
  dbdx = (dedx * s - e * dsdx) / (s * s);
  dbdy = (dedy * s - e * dsdy) / (s * s);
}

// NDC position of a pixel centre.
vec2 pixelNdc(uvec2 pixel, vec2 viewportSize) { return (vec2(pixel) + 0.5) / viewportSize * 2.0 - 1.0; }

#endif
