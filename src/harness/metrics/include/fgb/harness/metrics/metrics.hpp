// Image comparison metrics: max abs error, RMSE, PSNR, share of pixels over a per-channel threshold,
// non-finite counts and FLIP (LDR-FLIP for display images, HDR-FLIP for linear HDR images).
#pragma once

#include <fgb/harness/flip/flip.hpp>
#include <fgb/harness/image/image.hpp>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

struct MetricOptions {
  double channelThreshold = -1.0;  // < 0: default of the domain (2/255 for sRGB, 0.01 for linear)
  double pixelsPerDegree = defaultPixelsPerDegree();
  bool flip = true;
};

inline constexpr double kDefaultSrgbChannelThreshold = 2.0 / 255.0;
inline constexpr double kDefaultLinearChannelThreshold = 0.01;

struct FlipStatistics {
  std::string mode;  // "ldr" | "hdr"
  double mean = 0.0, p50 = 0.0, p95 = 0.0, p99 = 0.0, max = 0.0;
  double startExposure = 0.0, stopExposure = 0.0;  // HDR-FLIP only
  int exposures = 0;                                // HDR-FLIP only
};

struct ImageMetrics {
  uint32_t width = 0, height = 0;
  std::string domain;  // "srgb" (compared as encoded display values) | "linear"
  double maxAbsError = 0.0;
  double rmse = 0.0;
  double psnr = 0.0;    // dB; +infinity for identical images (null in JSON)
  double peak = 1.0;    // PSNR's peak value: 1 for sRGB, max(1, largest reference value) for linear
  double channelThreshold = 0.0;
  double shareOverThreshold = 0.0;  // pixels with any RGB channel differing by more than the threshold
  uint64_t nonFiniteReference = 0, nonFiniteTest = 0;  // NaN/Inf pixels: always a failure
  std::optional<FlipStatistics> flip;

  bool hasNonFinite() const { return nonFiniteReference + nonFiniteTest > 0; }
};

struct Comparison {
  ImageMetrics metrics;
  // Per-pixel error for the heat map: FLIP when computed, else max abs channel error / max.
  std::vector<float> errorMap;
  std::vector<uint8_t> nonFiniteMask;  // 1 where either image has NaN/Inf
};

// Images must have the same size (std::invalid_argument otherwise; callers name the files).
// Mixed encodings are compared in sRGB: the linear image is encoded (clamped) first.
Comparison compareImages(const Image& reference, const Image& test, const MetricOptions& options = {});

// Summary statistics of a FLIP map (mean and percentiles, exact).
FlipStatistics summarizeFlip(const std::vector<float>& errors, std::string mode);

nlohmann::json toJson(const ImageMetrics& metrics);

// Magma-like colour map of per-pixel errors in [0, 1] (NaN/Inf pixels in bright green), sRGB.
Image heatMap(const std::vector<float>& errors, const std::vector<uint8_t>& nonFiniteMask, uint32_t width, uint32_t height);

}  // namespace fgb::harness
