#version 460
// "Exposure", second dispatch (one workgroup): adds the partial sums in a fixed order, turns the
// log-average luminance into the exposure key / L_avg (Reinhard et al. 2002) and updates the
// exposure state (see ExposureGpu in gpu_types.hpp): this frame's tone mapping uses it at once
// (no temporal adaptation, so every frame of a static scene is the same, as goldens need) and the
// next frame's lighting is pre-exposed with it.
#extension GL_GOOGLE_include_directive : require
#include "include/common.glsl"
#include "include/exposure.glsl"
#include "renderer/shared/post.h"

layout(local_size_x = FGB_EXPOSURE_UPDATE_GROUP_SIZE) in;

layout(push_constant) uniform Push { ExposureUpdatePush pc; };

FGB_STORAGE_BUFFER(ExposureWriteBlock, fgbExposuresWrite, ) { Exposure state; } fgbExposuresWrite[FGB_MAX_STORAGE_BUFFERS];

shared vec2 sharedSums[256];

void main() {
  uint index = gl_LocalInvocationIndex;
  vec2 sum = vec2(0.0);
  for (uint i = index; i < pc.partialCount; i += 256u) sum += fgbVec4s[pc.partials].values[i].xy;
  sharedSums[index] = sum;
  barrier();
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    if (index < stride) sharedSums[index] += sharedSums[index + stride];
    barrier();
  }
  if (index != 0u) return;
  Exposure state = fgbExposuresWrite[pc.state].state;
  vec2 total = sharedSums[0];
  if (total.y > 0.0) {
    // Undo this frame's pre-exposure: the average is of scene-referred luminance.
    float averageLog2 = total.x / total.y - log2(state.preExposure);
    float exposure = clamp(pc.key * exp2(-averageLog2), kMinExposure, kMaxExposure);
    state.averageLuminance = exp2(averageLog2);
    state.tonemapScale = exposure / state.preExposure;
    state.exposure = exposure;
  } else {
    state.tonemapScale = state.exposure / state.preExposure;  // nothing lit: keep the exposure
  }
  state.preExposure = state.exposure;  // the next frame is lit with this frame's exposure
  fgbExposuresWrite[pc.state].state = state;
}
