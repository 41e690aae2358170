#version 460
// "Particle Render": camera-facing quads, one instance per alive particle (indexed quad 0-1-2 2-1-3).
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/opaque_depth.glsl"
#include "include/particles.glsl"

layout(push_constant) uniform Push { ParticleRenderPush pc; };

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec2 outCorner;

void main() {
  FrameConstants frame = fgbFrames[pc.frame].frame;
  Particle p = fgbParticlesRead[pc.particles].particles[fgbUintsRead[pc.aliveList].values[gl_InstanceIndex]];
  Emitter e = fgbEmitters[pc.emitters].emitters[p.emitter];
  float t = clamp(p.positionAge.w / max(p.velocityLifetime.w, 1e-4), 0.0, 1.0);
  float size = mix(e.speedSize.z, e.speedSize.w, t);
  vec2 corner = vec2(gl_VertexIndex & 1, (gl_VertexIndex >> 1) & 1) * 2.0 - 1.0;
  vec3 right = vec3(frame.view[0][0], frame.view[1][0], frame.view[2][0]);
  vec3 up = vec3(frame.view[0][1], frame.view[1][1], frame.view[2][1]);
  // Particles live in the scene camera's render space: anchorOffset moves them into this frame's.
  vec3 world = p.positionAge.xyz + frame.anchorOffset.xyz + (right * corner.x + up * corner.y) * size;
  outColor = mix(e.colorStart, e.colorEnd, t);
  // Emitted radiance, pre-exposed like all lighting and kept within R16F's range.
  outColor.rgb = min(outColor.rgb * preExposure(frame), vec3(kHalfMax));
  outCorner = corner;
  gl_Position = frame.viewProj * vec4(world, 1.0);
}
