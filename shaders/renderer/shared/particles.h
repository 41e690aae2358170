// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): GPU particles' structs and push blocks
// (src/renderer/features/particles/; particle_emit.comp, particle_update.comp, particle.vert,
// particle.frag, shaders/renderer/include/particles.glsl).
#ifndef FGB_RENDERER_SHARED_PARTICLES_H
#define FGB_RENDERER_SHARED_PARTICLES_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/opaque_depth.h"

#define FGB_PARTICLE_GROUP_SIZE 64  // particle_emit.comp (one workgroup per emitter), particle_update.comp

FGB_GPU_BEGIN

struct Particle {
  vec4 positionAge;       // xyz, age in seconds
  vec4 velocityLifetime;  // xyz, lifetime (0: dead)
  uint emitter;
  uint alive;
  uint pad0;
  uint pad1;
};
FGB_CHECK_SIZE(Particle, 48)

struct Emitter {
  vec4 positionRate;   // xyz, particles per second
  vec4 directionCone;  // xyz unit, cos(cone half-angle)
  vec4 colorStart;
  vec4 colorEnd;
  vec4 speedSize;      // speed min, speed max, size start, size end
  vec4 lifetime;       // x: seconds
  uvec4 seed;          // x: seed
};
FGB_CHECK_SIZE(Emitter, 112)

// particle_emit.comp.
struct ParticleEmitPush {
  uint emitters;
  uint particles;
  uint freeList;  // [0] count, [1..] free slots
  uint frame;     // FrameConstants: the simulation step and its index
};
FGB_CHECK_PUSH(ParticleEmitPush, 16)

// particle_update.comp.
struct ParticleUpdatePush {
  uint particles;
  uint freeList;
  uint drawArgs;  // DrawCommand: instanceCount counts alive particles
  uint aliveList;
  uint poolSize;
  uint frame;     // FrameConstants: the simulation step
};
FGB_CHECK_PUSH(ParticleUpdatePush, 24)

// "Particle Render" (particle.vert, particle.frag).
struct ParticleRenderPush {
  uint frame;
  uint particles;
  uint emitters;
  uint aliveList;
  OpaqueDepthTest opaqueDepth;  // read by particle.frag
};
FGB_CHECK_PUSH(ParticleRenderPush, 28)

FGB_GPU_END

#endif
