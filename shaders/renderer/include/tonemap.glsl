// "Tone mapping" (thesis): L = 1 - exp(-L_hdr * exposure), plus the bloom texture when present.
// Shared by tonemap.frag (forward path: the hardware applies the sRGB curve of the display target)
// and tonemap.comp (visibility-buffer path: encodes sRGB itself into an 8-bit storage image), so
// the two cannot drift. The HDR image is pre-exposed (L_hdr * preExposure): the exposure left to
// apply is the state's tonemapScale.
#ifndef FGB_TONEMAP_GLSL
#define FGB_TONEMAP_GLSL

#include "common.glsl"
#include "renderer/shared/post.h"

layout(push_constant) uniform Push { TonemapPush pc; };

// The display value (linear, before the sRGB curve) of output pixel `pixel`, whose centre is at
// `uv` in the bloom texture (the bloom texture has one mip level).
vec3 tonemapPixel(ivec2 pixel, vec2 uv) {
  vec3 hdr = texelFetch(fgbTextures[pc.hdrTexture], pixel, 0).rgb;
  if (pc.bloomTexture != FGB_NONE) {
    hdr += pc.bloomIntensity *
           textureLod(sampler2D(fgbTextures[pc.bloomTexture], fgbSamplers[pc.linearSampler]), uv, 0.0).rgb;
  }
  float scale = fgbExposures[pc.exposure].state.tonemapScale;
  return 1.0 - exp(-max(hdr, vec3(0.0)) * scale) + pc.bias;  // bias: debug.inject_bias
}

#endif
