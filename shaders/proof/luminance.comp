#version 460
// Proof scene, debug node: per-pixel luminance into a buffer nobody reads (the graph culls it).
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
FGB_STORAGE_BUFFER(Luminance, luminance, writeonly) { float values[]; } fgbLuminance[FGB_MAX_STORAGE_BUFFERS];

layout(push_constant) uniform Push {
  uint hdrTexture;
  uint outputBuffer;
  uint width;
  uint height;
} pc;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.width || p.y >= pc.height) return;
  vec3 c = fgbFetch(pc.hdrTexture, ivec2(p)).rgb;
  fgbLuminance[pc.outputBuffer].values[p.y * pc.width + p.x] = dot(c, vec3(0.2126, 0.7152, 0.0722));
}
