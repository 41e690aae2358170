// FLIP image difference (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images",
// HPG 2020) and HDR-FLIP (Andersson et al., "Visualizing Errors in Rendered High Dynamic Range
// Images", EG 2021), implemented from the papers. Per-pixel errors are in [0, 1]; 0 = identical.
#pragma once

#include <fgb/harness/image/image.hpp>

#include <cstdint>
#include <vector>

namespace fgb::harness {

// Observer: a 0.7 m wide 3840-pixel monitor seen from 0.7 m, as in the paper (≈ 67 pixels/degree).
double defaultPixelsPerDegree();

struct FlipMap {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> error;  // width * height, row-major
};

// LDR-FLIP. Inputs are display images: sRGB-encoded or linear, in [0, 1] (values outside are
// clamped; non-finite values count as 0). Sizes must match (std::invalid_argument otherwise).
FlipMap ldrFlip(const Image& reference, const Image& test, double pixelsPerDegree = defaultPixelsPerDegree());

struct HdrFlipResult {
  FlipMap map;  // per pixel: the maximum LDR-FLIP error over the exposures
  double startExposure = 0.0;
  double stopExposure = 0.0;
  int exposures = 0;
};

// The paper's exposure range for the ACES tone mapper: the start exposure maps the reference's
// largest luminance to 0.85 after tone mapping, the stop exposure maps its median luminance there.
struct ExposureRange {
  double start = 0.0;
  double stop = 0.0;
  int count = 2;  // max(2, ceil(stop - start))
};
ExposureRange hdrExposureRange(const Image& linearReference);

// ACES (Narkowicz fit, as HDR-FLIP uses it) of 2^exposure * value, clamped to [0, 1].
float acesToneMap(float value, double exposure);

// HDR-FLIP of two linear HDR images: LDR-FLIP of the tone-mapped pair at each exposure, max per pixel.
HdrFlipResult hdrFlip(const Image& reference, const Image& test, double pixelsPerDegree = defaultPixelsPerDegree());

}  // namespace fgb::harness
