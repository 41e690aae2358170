#version 460
// "Particle Update": ages and moves alive particles; dead ones go back to the free list, alive ones
// are appended to the draw list and counted into the indirect draw's instance count (reset by the
// "Particle Reset" node, never by this pass).
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/particles.glsl"

layout(local_size_x = FGB_PARTICLE_GROUP_SIZE) in;

layout(push_constant) uniform Push { ParticleUpdatePush pc; };

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= pc.poolSize) return;
  Particle p = fgbParticles[pc.particles].particles[slot];
  if (p.alive == 0u) return;
  p.positionAge.w += PARTICLE_DT;
  if (p.positionAge.w >= p.velocityLifetime.w) {
    p.alive = 0u;
    fgbParticles[pc.particles].particles[slot] = p;
    uint top = atomicAdd(fgbUints[pc.freeList].values[0], 1u);
    fgbUints[pc.freeList].values[top + 1u] = slot;
    return;
  }
  vec3 velocity = p.velocityLifetime.xyz * (1.0 - 0.5 * PARTICLE_DT) + vec3(0.0, 0.4, 0.0) * PARTICLE_DT;  // drag, buoyancy
  p.velocityLifetime.xyz = velocity;
  p.positionAge.xyz += velocity * PARTICLE_DT;
  fgbParticles[pc.particles].particles[slot] = p;
  uint index = atomicAdd(fgbCommands[pc.drawArgs].commands[0].instanceCount, 1u);
  fgbUints[pc.aliveList].values[index] = slot;
}
