#version 460
// Writes value + index into a uint storage buffer, or adds to it (mode 1): tests use it for
// same-buffer write-after-write and read-after-write chains.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"

layout(local_size_x = 64) in;
FGB_STORAGE_BUFFER(Words, words, ) { uint values[]; } fgbWords[FGB_MAX_STORAGE_BUFFERS];

layout(push_constant) uniform Push {
  uint bufferIndex;
  uint count;
  uint value;
  uint mode;  // 0: values[i] = value + i; 1: values[i] += value
} pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (pc.mode == 0u) fgbWords[pc.bufferIndex].values[i] = pc.value + i;
  else fgbWords[pc.bufferIndex].values[i] += pc.value;
}
