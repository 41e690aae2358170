#version 460
// The last dispatch of "Visibility Raster": each pixel's depth, from its finished visibility word,
// into the float buffer that "Visibility Depth Resolve" copies into the depth target (the far value
// where nothing was drawn). Done here rather than in "Material Shade", so the copy depends on the
// raster only and the GPU can run it alongside the shading.
#extension GL_GOOGLE_include_directive : require
#include "../include/visbuffer_triangle.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  loadFrameGlobals();
  uvec2 pixel = gl_GlobalInvocationID.xy;
  uvec2 size = uvec2(viewportSize());
  if (any(greaterThanEqual(pixel, size))) return;
  uint index = pixel.y * size.x + pixel.x;
  uint64_t word = visWordsRead[pc.words].words[index];
  visFloats[pc.depthOut].values[index] = word == 0ul ? (reversedZ() ? 0.0 : 1.0) : depthFromKey(uint(word >> 32), reversedZ());
}
