// GPU particles: pool, emitters and the shared random function (mirrors particles/particle_feature.cpp).
#ifndef FGB_RENDERER_PARTICLES_GLSL
#define FGB_RENDERER_PARTICLES_GLSL

#define PARTICLE_DT (1.0 / 60.0)

struct Particle {
  vec4 positionAge;       // xyz, age in seconds
  vec4 velocityLifetime;  // xyz, lifetime (0: dead)
  uint emitter;
  uint alive;
  uint pad0;
  uint pad1;
};

struct Emitter {
  vec4 positionRate;    // xyz, particles per second
  vec4 directionCone;   // xyz unit, cos(cone half-angle)
  vec4 colorStart;
  vec4 colorEnd;
  vec4 speedSize;       // speed min, speed max, size start, size end
  vec4 lifetime;        // x: seconds
  uvec4 seed;           // x: seed
};

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
