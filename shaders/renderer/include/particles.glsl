// GPU particles: pool and emitter buffers (structs and push blocks: renderer/shared/particles.h)
// and the shared random function.
#ifndef FGB_RENDERER_PARTICLES_GLSL
#define FGB_RENDERER_PARTICLES_GLSL

#include "renderer/shared/particles.h"

// The simulation advances one fixed step per frame, the run's time step (FrameConstants.simulation.x,
// 0 while a still view holds its particles; step.x counts the steps).
#define PARTICLE_DT (fgbFrames[pc.frame].frame.simulation.x)
#define PARTICLE_STEP (fgbFrames[pc.frame].frame.step.x)

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
