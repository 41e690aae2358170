// Golden images: golden/<scene>/<device-class>/<config>.{png,exr,json}. The JSON holds the
// thresholds and how the golden was made (device, driver, tool version, config, measured noise).
#pragma once

#include <fgb/harness/image/image.hpp>
#include <fgb/harness/metrics/metrics.hpp>
#include <fgb/renderer/workload.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

// "builtin:proof" -> "proof"; "scenes/atrium.json" -> "atrium".
std::string sceneName(const std::string& scenePath);
// "lavapipe" for CPU devices, else the device name in lower case with runs of other characters
// replaced by '-' ("nvidia-geforce-gtx-1660-ti").
std::string deviceClass(const render::DeviceDescription& device);

inline constexpr const char* kDefaultGoldenConfig = "default";

// Limits per image kind; an absent limit is not checked. NaN/Inf always fail.
struct Thresholds {
  std::optional<double> flipMean, flipP99, rmse, maxAbsError, shareOverThreshold, psnrMin;
  std::optional<double> channelThreshold;  // the per-channel threshold used for the share
};

struct GoldenConfig {
  uint32_t width = 0, height = 0, msaa = 0;  // 0: not recorded
  uint32_t frames = 0, warmup = 0;
  bool hasWarmup = false;  // warm-up 0 is a valid recorded value
  std::map<std::string, std::string> knobs;
};

struct Golden {
  std::filesystem::path jsonPath;
  std::filesystem::path displayImage;  // PNG, compared with the tone-mapped frame
  std::filesystem::path hdrImage;      // EXR, compared with the HDR frame (optional)
  GoldenConfig config;
  Thresholds display, hdr;
  nlohmann::json document;  // the whole file, for metadata
};

// `where` is a golden JSON file or a directory holding default.json. Missing or malformed golden
// -> InputError naming the file.
Golden loadGolden(const std::filesystem::path& where);

struct ImageVerdict {
  std::string kind;  // "display" | "hdr"
  ImageMetrics metrics;
  std::vector<std::string> failures;  // "flip_mean 0.031 > 0.02", "3 NaN/Inf pixels in test"
};

struct GoldenResult {
  std::string file;
  std::string verdict = "none";  // "pass" | "fail" | "none"
  std::vector<ImageVerdict> images;
  std::string diffImage;  // heat map written on failure ("" if none)
};

ImageVerdict judgeImage(const std::string& kind, const ImageMetrics& metrics, const Thresholds& limits);
MetricOptions metricOptionsFor(const Thresholds& limits);

// The contract's timings.json "golden" object.
nlohmann::json toJson(const GoldenResult& result);

// Thresholds derived from the noise between repeated renders: comfortably above the noise, never
// below a floor that tolerates 8-bit rounding.
Thresholds thresholdsFromNoise(const std::optional<ImageMetrics>& noise, bool hdr);
nlohmann::json toJson(const Thresholds& thresholds);
Thresholds thresholdsFromJson(const nlohmann::json& j, const std::filesystem::path& file, const std::string& where);

}  // namespace fgb::harness
