// GPU particles: pool and emitter buffers (structs and push blocks: renderer/shared/particles.h)
// and the shared random function.
#ifndef FGB_RENDERER_PARTICLES_GLSL
#define FGB_RENDERER_PARTICLES_GLSL

#include "renderer/shared/particles.h"

#define PARTICLE_DT (1.0 / 60.0)

FGB_STORAGE_BUFFER(ParticleBlock, fgbParticles, ) { Particle particles[]; } fgbParticles[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(ParticleReadBlock, fgbParticlesRead) { Particle particles[]; } fgbParticlesRead[FGB_MAX_STORAGE_BUFFERS];
FGB_READONLY_STORAGE_BUFFER(EmitterBlock, fgbEmitters) { Emitter emitters[]; } fgbEmitters[FGB_MAX_STORAGE_BUFFERS];

// PCG hash: deterministic per (seed, frame, index).
uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float random01(inout uint state) {
  state = pcgHash(state);
  return float(state >> 8) / 16777216.0;
}

#endif
