// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the opaque-depth test of the colour passes
// drawn after the visibility buffer's opaque scene, a member of their push blocks
// (shaders/renderer/include/opaque_depth.glsl; features::OpaqueDepthSource fills it).
#ifndef FGB_RENDERER_SHARED_OPAQUE_DEPTH_H
#define FGB_RENDERER_SHARED_OPAQUE_DEPTH_H

#include "fgb/rhi/shared/prelude.h"

FGB_GPU_BEGIN

struct OpaqueDepthTest {
  uint depths;     // float per pixel; FGB_NONE: nothing to test against (forward, or nothing opaque)
  uint rowStride;  // pixels per row (the scene passes' width)
  uint compareOp;  // rhi::CompareOp = VkCompareOp: bit 0 passes less, bit 1 equal, bit 2 greater
};
FGB_CHECK_SIZE(OpaqueDepthTest, 12)

FGB_GPU_END

#endif
