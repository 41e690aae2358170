#version 460
// debug.slow_pass: a dispatch that only costs time. Each invocation runs `iterations` steps of a
// xorshift chain (no closed form, so no compiler can fold the loop) and stores the result in a
// scratch buffer of the executor's own that nothing reads; it touches no frame-graph resource.
// Its own descriptor set (set 0 of its own pipeline layout), not the bindless tables.
layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) writeonly buffer Scratch { uint values[]; } scratch;

layout(push_constant) uniform Push {
  uint iterations;
  uint seed;
} pc;

void main() {
  uint x = pc.seed ^ (gl_LocalInvocationIndex * 0x9E3779B9u) | 1u;
  for (uint i = 0u; i < pc.iterations; ++i) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    x += i;
  }
  scratch.values[gl_LocalInvocationIndex] = x;
}
