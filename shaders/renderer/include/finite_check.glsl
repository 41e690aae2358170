// "Finite Check" (--check-finite): counts the pixels of one float texture that hold a NaN, an Inf,
// or a magnitude above half of R16F's maximum (32752, a value one doubling away from overflow), in
// any channel. Each workgroup counts 8x8 pixels in shared memory and adds its totals to the pass's
// slot of the counters buffer (reset every frame). FGB_MULTISAMPLE: every sample of an MSAA texture.
#ifndef FGB_FINITE_CHECK_GLSL
#define FGB_FINITE_CHECK_GLSL

#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_FINITE_CHECK_GROUP_SIZE, local_size_y = FGB_FINITE_CHECK_GROUP_SIZE) in;

layout(push_constant) uniform Push { FiniteCheckPush pc; };

#ifdef FGB_MULTISAMPLE
layout(set = 0, binding = FGB_BINDING_SAMPLED_TEXTURES) uniform texture2DMS fgbTexturesMs[FGB_MAX_SAMPLED_TEXTURES];
vec4 fetchSample(ivec2 texel, int s) { return texelFetch(fgbTexturesMs[pc.source], texel, s); }
#else
vec4 fetchSample(ivec2 texel, int s) { return texelFetch(fgbTextures[pc.source], texel, 0); }
#endif

const float kHalfOfR16fMax = 32752.0;

shared uint sharedNan;
shared uint sharedInf;
shared uint sharedLarge;

void main() {
  if (gl_LocalInvocationIndex == 0u) {
    sharedNan = 0u;
    sharedInf = 0u;
    sharedLarge = 0u;
  }
  barrier();
  const ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (all(lessThan(texel, pc.size))) {
    bool nan = false, inf = false, large = false;
    for (int s = 0; s < int(pc.samples); ++s) {
      const vec4 v = fetchSample(texel, s);
      nan = nan || any(isnan(v));
      inf = inf || any(isinf(v));
      large = large || any(greaterThan(abs(v), vec4(kHalfOfR16fMax)));
    }
    if (nan) atomicAdd(sharedNan, 1u);
    if (inf) atomicAdd(sharedInf, 1u);
    if (large && !inf) atomicAdd(sharedLarge, 1u);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    const uint base = pc.slot * (kFiniteCheckSlotBytes / 4u);
    if (sharedNan != 0u) atomicAdd(fgbUints[pc.counters].values[base + 0u], sharedNan);
    if (sharedInf != 0u) atomicAdd(fgbUints[pc.counters].values[base + 1u], sharedInf);
    if (sharedLarge != 0u) atomicAdd(fgbUints[pc.counters].values[base + 2u], sharedLarge);
  }
}

#endif
