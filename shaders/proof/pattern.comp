#version 460
// Proof scene, compute node: writes the vertices of an animated fan of triangles (position in NDC,
// HDR colour) into a storage buffer that the draw node then reads as its vertex buffer.
#extension GL_GOOGLE_include_directive : require
#include "bindless.glsl"

layout(local_size_x = 64) in;

struct Vertex { vec4 position; vec4 color; };
FGB_STORAGE_BUFFER(Vertices, vertices, writeonly) { Vertex v[]; } fgbVertexBuffers[FGB_MAX_STORAGE_BUFFERS];

layout(push_constant) uniform Push {
  uint vertexBuffer;
  uint triangleCount;
  float time;
} pc;

void main() {
  uint tri = gl_GlobalInvocationID.x;
  if (tri >= pc.triangleCount) return;
  const float tau = 6.28318530718;
  float a0 = tau * float(tri) / float(pc.triangleCount) + 0.25 * pc.time;
  float a1 = tau * float(tri + 1) / float(pc.triangleCount) + 0.25 * pc.time;
  float radius = 0.8;
  // Alternating bright (HDR, > 1) and dim sectors, so tone mapping has something to compress.
  vec4 color = (tri % 2u == 0u) ? vec4(4.0, 1.0, 0.25, 1.0) : vec4(0.1, 0.4, 1.0, 1.0);
  uint base = tri * 3u;
  fgbVertexBuffers[pc.vertexBuffer].v[base + 0u] = Vertex(vec4(0.0, 0.0, 0.0, 1.0), color);
  fgbVertexBuffers[pc.vertexBuffer].v[base + 1u] = Vertex(vec4(radius * cos(a0), radius * sin(a0), 0.0, 1.0), color);
  fgbVertexBuffers[pc.vertexBuffer].v[base + 2u] = Vertex(vec4(radius * cos(a1), radius * sin(a1), 0.0, 1.0), color);
}
