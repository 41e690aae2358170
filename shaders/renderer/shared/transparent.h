// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the visibility-buffer path's compute
// transparent passes (render.transparent=compute; src/renderer/features/transparent_compute/):
// "Transparent Raster" (transparent_raster.comp) keeps, per pixel, the K nearest transparent
// fragments in front of the opaque depth; "Transparent Shade" (transparent_shade.comp) shades them
// and blends them far to near over the HDR image. Both take VisPush (renderer/shared/visbuffer.h),
// so the visibility buffer's triangle setup and material code serve them unchanged; its fields
// mean, for these nodes:
//   draws     "Transparent Cluster Cull"'s packed draws in the cluster form
//             (kTransparentCullClusterIds: firstIndex is the ClusterData index)
//   args      that node's draw count (uint)
//   counters  TransparentCounters
//   largeList large triangles' fragment ids (uint each), largeCapacity of them
//   words     the K-buffer (persistent, empty between frames): FGB_TRANSPARENT_K planes of one
//             uint64 per pixel, slot i of pixel p at i * pixels + p (the shade's early out
//             reads plane 0 alone), then one uint64 per shade tile, at K * pixels + tile: kEmpty
//             until the raster's first fragment in the tile lists it, emptied again by the shade
//   tileJobs  the tile list: a count, then the tiles (y * tiles across + x) that received a
//             fragment this frame, one "Transparent Shade" workgroup each
//   depthOut  the opaque depth "Material Shade" wrote (read only), rows of viewport width
//   depthCompare the opaque depth test's comparison (OpaqueDepthTest::compareOp)
//   hdr       the HDR image (read and written by the shade)
#ifndef FGB_RENDERER_SHARED_TRANSPARENT_H
#define FGB_RENDERER_SHARED_TRANSPARENT_H

#include "fgb/rhi/shared/prelude.h"

// Fragments kept per pixel: the K nearest, sorted. A pixel behind more transparent layers than
// this loses the farthest ones (counted: TransparentCounters::dropped).
#define FGB_TRANSPARENT_K 4
// transparent_raster.comp, small triangles: one workgroup per packed cluster draw, one invocation
// per triangle (clusters hold at most 128, kClusterTriangleBits).
#define FGB_TRANSPARENT_RASTER_GROUP_SIZE 128
// A triangle whose pixel box holds more than this many pixel centres goes to the large list,
// rasterised by the node's second dispatch: FGB_TRANSPARENT_LARGE_GROUPS workgroups (of the same
// size) walk the list, each taking one triangle at a time and sharing its pixels.
#define FGB_TRANSPARENT_SMALL_PIXELS 64
#define FGB_TRANSPARENT_LARGE_GROUPS 256
// transparent_shade.comp: one workgroup of 8 x 8 pixels per listed tile, the tiles being this
// size; the workgroups spill into gl_WorkGroupID.y past FGB_TRANSPARENT_SHADE_GROUPS_X.
#define FGB_TRANSPARENT_SHADE_GROUP_SIZE 8
#define FGB_TRANSPARENT_SHADE_GROUPS_X 65535

FGB_GPU_BEGIN

// Reset every frame ("Transparent Clear": zeroes, shadeGroupsZ 1); the statistics read them back.
struct TransparentCounters {
  uint largeTriangles;  // appended to the large list (slots: the first largeCapacity of them)
  uint largeOverflow;   // of those, past the list's capacity: rasterised by their small invocation
  uint inserted;        // fragments in front of the opaque depth, offered to the K-buffer
  uint dropped;         // fragments that fell off the end of a full K-buffer (the farthest)
  uint tilesListed;     // tiles some fragment landed in: "Transparent Shade"'s workgroups
  // "Transparent Shade"'s indirect dispatch, one workgroup per listed tile: (min(n, GROUPS_X),
  // ceil(n / GROUPS_X), 1), raised by the raster as it lists tiles.
  uint shadeGroupsX;
  uint shadeGroupsY;
  uint shadeGroupsZ;  // last: Clear fills the rest with zeroes, it with 1, the ranges disjoint
};
FGB_CHECK_SIZE(TransparentCounters, 32)

FGB_GPU_END

#endif
