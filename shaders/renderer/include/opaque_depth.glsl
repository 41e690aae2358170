// The depth test of the colour passes drawn after the opaque scene on the visibility-buffer path
// ("Mesh Render Transparent", "Particle Render"; features::DepthTest::OpaqueDepthBuffer): they have
// no depth attachment, and test each fragment against the opaque depth "Material Shade" wrote (a
// float per pixel) as the attachment would on the forward path: same comparison, same depths.
#ifndef FGB_RENDERER_OPAQUE_DEPTH_GLSL
#define FGB_RENDERER_OPAQUE_DEPTH_GLSL
#include "common.glsl"
#include "renderer/shared/opaque_depth.h"  // OpaqueDepthTest, a push-constant member

// Whether a fragment at `fragCoord` (gl_FragCoord, single-sampled) passes: its depth compared with
// the stored one, like the fixed-function test (a NaN on either side compares as nothing).
bool passesOpaqueDepth(OpaqueDepthTest test, vec4 fragCoord) {
  if (test.depths == FGB_NONE) return true;
  uvec2 pixel = uvec2(fragCoord.xy);
  float stored = uintBitsToFloat(fgbUintsRead[test.depths].values[pixel.y * test.rowStride + pixel.x]);
  float z = fragCoord.z;
  uint outcome = (z < stored ? 1u : 0u) | (z == stored ? 2u : 0u) | (z > stored ? 4u : 0u);
  return (test.compareOp & outcome) != 0u;
}

#endif
