#version 460
// "Visibility Clear" of the image backing (render.vis_backing=image): zeroes the R64_UINT
// visibility image, one invocation per pixel (0: no triangle, see visbuffer.glsl). A dispatch
// rather than vkCmdClearColorImage: VK_EXT_shader_image_atomic_int64 guarantees R64_UINT storage
// images with atomics (optimal tiling), not that they can be a transfer destination.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_nonuniform_qualifier : require
#define FGB_VIS_BACKING_IMAGE
#include "../include/visbuffer.glsl"

layout(local_size_x = FGB_VIS_CLEAR_GROUP_SIZE, local_size_y = FGB_VIS_CLEAR_GROUP_SIZE) in;

layout(push_constant) uniform Push { ClearPush pc; };

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= pc.width || pixel.y >= pc.height) return;
  imageStore(visImages[pc.words], ivec2(pixel), u64vec4(0ul));
}
