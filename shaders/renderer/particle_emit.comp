#version 460
// "Particle Emit": one workgroup per emitter spawns this frame's particles into slots popped from
// the free list (a stack whose counter only decreases in this pass; Update pushes in its own node).
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/particles.glsl"

layout(local_size_x = FGB_PARTICLE_GROUP_SIZE) in;

layout(push_constant) uniform Push { ParticleEmitPush pc; };

void main() {
  Emitter e = fgbEmitters[pc.emitters].emitters[gl_WorkGroupID.x];
  // Deterministic spawn count: particles due by the end of this frame minus those due before it.
  uint due = uint(floor(float(PARTICLE_STEP + 1u) * PARTICLE_DT * e.positionRate.w));
  uint before = uint(floor(float(PARTICLE_STEP) * PARTICLE_DT * e.positionRate.w));
  uint spawn = due - before;
  for (uint i = gl_LocalInvocationIndex; i < spawn; i += 64u) {
    int top = int(atomicAdd(fgbUints[pc.freeList].values[0], uint(-1)));
    if (top <= 0) {
      atomicAdd(fgbUints[pc.freeList].values[0], 1u);  // pool exhausted: undo the pop
      return;
    }
    uint slot = fgbUints[pc.freeList].values[uint(top)];
    uint rng = e.seed.x * 9781u + PARTICLE_STEP * 6271u + i * 31u + gl_WorkGroupID.x;
    float cosTheta = mix(1.0, e.directionCone.w, random01(rng));
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    float phi = 2.0 * PI * random01(rng);
    vec3 axis = e.directionCone.xyz;
    vec3 side = normalize(abs(axis.y) < 0.99 ? cross(axis, vec3(0, 1, 0)) : cross(axis, vec3(1, 0, 0)));
    vec3 other = cross(axis, side);
    vec3 direction = axis * cosTheta + (side * cos(phi) + other * sin(phi)) * sinTheta;
    float speed = mix(e.speedSize.x, e.speedSize.y, random01(rng));
    Particle p;
    p.positionAge = vec4(e.positionRate.xyz, 0.0);
    p.velocityLifetime = vec4(direction * speed, e.lifetime.x * mix(0.75, 1.0, random01(rng)));
    p.emitter = gl_WorkGroupID.x;
    p.alive = 1u;
    fgbParticles[pc.particles].particles[slot] = p;
  }
}
