#version 460
// "SSAA Resolve", visibility-buffer path: one invocation per output pixel, the box filter of
// include/ssaa.glsl written to the output HDR image (storage usage on this path).
#extension GL_GOOGLE_include_directive : require
#include "include/ssaa.glsl"

layout(local_size_x = FGB_POST_GROUP_SIZE, local_size_y = FGB_POST_GROUP_SIZE) in;

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba16f) uniform writeonly image2D fgbImagesRgba16f[FGB_MAX_STORAGE_TEXTURES];

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(fgbImagesRgba16f[pc.target])))) return;
  imageStore(fgbImagesRgba16f[pc.target], pixel, ssaaBoxMean(pixel));
}
