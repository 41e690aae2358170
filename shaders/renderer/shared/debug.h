// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the faults the debug knobs inject, so tests
// of per-pass goldens (issue 29) have a known pass to find. debug.inject_bias=PASS adds
// kInjectedBias to every pixel that pass writes (its shader's flag or push field); debug.inject_nan
// writes a NaN at the centre pixel (tests of --check-finite).
#ifndef FGB_RENDERER_SHARED_DEBUG_H
#define FGB_RENDERER_SHARED_DEBUG_H

#include "fgb/rhi/shared/prelude.h"

FGB_GPU_BEGIN

// In the units the pass writes (pre-exposed HDR radiance; display values before the sRGB curve):
// far above any rounding, small enough that the frame still looks like itself.
const float kInjectedBias = 0.05;
// The bloom pushes' `inject` field.
const uint kInjectNan = 1u;
const uint kInjectBias = 2u;

// debug.view, FrameConstants::counts.w: render_settings.hpp's DebugView (static_asserts there).
const uint kDebugViewLightComplexity = 1u;  // every path: lights evaluated per pixel
const uint kDebugViewLod = 2u;              // paths that draw clusters: each cluster's LOD level
const uint kDebugViewClusters = 3u;         // paths that draw clusters: a colour per cluster

FGB_GPU_END

#endif
