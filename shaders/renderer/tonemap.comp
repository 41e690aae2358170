#version 460
// "Tone mapping", visibility-buffer path: one invocation per output pixel, same maths as
// tonemap.frag (include/tonemap.glsl). Storage images cannot be sRGB on most devices, so the
// display image is R8G8B8A8_UNORM here and holds sRGB-encoded values, the bytes the sRGB target
// of the forward path holds (the encode is the sRGB transfer function, then the UNORM store's
// round to nearest).
#extension GL_GOOGLE_include_directive : require
#include "include/tonemap.glsl"

layout(local_size_x = FGB_POST_GROUP_SIZE, local_size_y = FGB_POST_GROUP_SIZE) in;

layout(set = 0, binding = FGB_BINDING_STORAGE_TEXTURES, rgba8) uniform writeonly image2D fgbImagesRgba8[FGB_MAX_STORAGE_TEXTURES];

vec3 linearToSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(fgbImagesRgba8[pc.display]);
  if (any(greaterThanEqual(pixel, size))) return;
  vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
  imageStore(fgbImagesRgba8[pc.display], pixel, vec4(linearToSrgb(tonemapPixel(pixel, uv)), 1.0));
}
