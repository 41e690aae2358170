// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): push blocks and workgroup sizes of the
// full-screen passes after the scene: SSAA resolve, exposure, bloom, tone mapping and the finite
// check (src/renderer/features/{ssaa,exposure,bloom,tonemap,finite_check}/).
#ifndef FGB_RENDERER_SHARED_POST_H
#define FGB_RENDERER_SHARED_POST_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/debug.h"

#define FGB_POST_GROUP_SIZE 8             // ssaa_resolve.comp, tonemap.comp: 8 x 8 pixels
#define FGB_BLOOM_GROUP_SIZE 8            // bloom_down.comp, bloom_up.comp: 8 x 8 texels
#define FGB_LUMINANCE_GROUP_SIZE 16       // luminance_reduce.comp: 16 x 16 invocations, 2 x 2 pixels each
#define FGB_EXPOSURE_UPDATE_GROUP_SIZE 256  // exposure_update.comp: one workgroup
#define FGB_FINITE_CHECK_GROUP_SIZE 8     // finite_check.comp, finite_check_ms.comp: 8 x 8 pixels

FGB_GPU_BEGIN

// "SSAA Resolve" (include/ssaa.glsl: ssaa_resolve.frag, ssaa_resolve.comp).
struct SsaaResolvePush {
  uint source;  // sampled texture index of the supersampled HDR image
  uint factor;  // render.ssaa, 2..8
  uint target;  // ssaa_resolve.comp: storage-image index of the output HDR image
};
FGB_CHECK_PUSH(SsaaResolvePush, 12)

// "Exposure": luminance_reduce.comp.
struct LuminanceReducePush {
  uint hdr;       // sampled texture index
  uint partials;  // vec4 per workgroup: x = sum of log2(luminance), y = pixels measured
  ivec2 size;
};
FGB_CHECK_PUSH(LuminanceReducePush, 16)

// "Exposure": exposure_update.comp.
struct ExposureUpdatePush {
  uint partials;
  uint partialCount;
  uint state;  // the exposure state (written through the writable binding)
  float key;   // display value the log-average luminance maps to (0.18: middle grey)
};
FGB_CHECK_PUSH(ExposureUpdatePush, 16)

// "Bloom": bloom_down.comp.
struct BloomDownPush {
  uint source;  // sampled texture index: the HDR image, or the previous level's in GENERAL
  uint linearSampler;
  uint target;          // storage image index
  uint firstMip;
  ivec2 sourceSize;
  ivec2 targetSize;
  float threshold;      // radiance; applied in the HDR image's pre-exposed units
  float knee;
  uint exposure;        // storage-buffer index of the exposure state
  uint inject;          // kInjectNan (debug.inject_nan=Bloom): the centre texel of the first level is a NaN
};
FGB_CHECK_PUSH(BloomDownPush, 48)

// "Bloom": bloom_up.comp.
struct BloomUpPush {
  uint source;  // sampled texture index in GENERAL (smaller level)
  uint target;  // storage image index (larger level)
  ivec2 sourceSize;
  ivec2 targetSize;
  float radius;        // in source texels
  uint inject;         // the first level: kInjectNan, its centre texel a NaN; kInjectBias, + kInjectedBias
  uint linearSampler;  // linear, clamp to edge
};
FGB_CHECK_PUSH(BloomUpPush, 40)

// "Tone mapping" (include/tonemap.glsl: tonemap.frag, tonemap.comp).
struct TonemapPush {
  uint hdrTexture;
  uint bloomTexture;  // FGB_NONE: no bloom
  uint linearSampler;
  uint exposure;      // storage-buffer index of the exposure state
  float bloomIntensity;
  uint display;       // tonemap.comp: storage-image index of the display image
  float bias;         // debug.inject_bias=Tone mapping: kInjectedBias, else 0
};
FGB_CHECK_PUSH(TonemapPush, 28)

// "Finite Check" (include/finite_check.glsl).
struct FiniteCheckPush {
  uint source;    // sampled texture index
  uint counters;  // storage buffer: kFiniteCheckSlotBytes per checked pass (nan, inf, over half max, -)
  uint slot;
  uint samples;
  ivec2 size;
};
FGB_CHECK_PUSH(FiniteCheckPush, 24)
const uint kFiniteCheckSlotBytes = 16u;  // uvec4

FGB_GPU_END

#endif
