// Shared by the auto-exposure compute shaders (luminance_reduce.comp, exposure_update.comp).
#ifndef FGB_RENDERER_EXPOSURE_GLSL
#define FGB_RENDERER_EXPOSURE_GLSL

// Exposure is kept within these bounds whatever the frame holds (an all-black or saturated frame).
const float kMinExposure = 1e-12;
const float kMaxExposure = 1e12;

// log2 of a pre-exposed pixel's luminance, clamped to what R16F can hold: a saturated (Inf) pixel
// counts as 65504, a black or NaN one as 2^-24 (half's smallest subnormal).
float log2PreExposedLuminance(vec3 rgb) {
  float l = luminance(rgb);
  l = l >= 0.0 ? min(l, 65504.0) : 0.0;  // NaN fails the comparison
  return log2(max(l, 5.96e-8));
}

#endif
