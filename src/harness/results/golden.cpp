#include <fgb/harness/results/golden.hpp>

#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace fgb::harness {
namespace {

std::optional<double> optionalLimit(const nlohmann::json& j, const char* key, const std::filesystem::path& file,
                                    const std::string& where) {
  if (!j.contains(key)) return std::nullopt;
  const double v = requireNumber(j, key, file, where);
  if (!std::isfinite(v) || v < 0.0) throw InputError(file.string() + ": field '" + where + "." + key + "' must be >= 0");
  return v;
}

void checkAbove(std::vector<std::string>& failures, const char* name, double value, const std::optional<double>& limit) {
  if (limit && value > *limit) failures.push_back(fmt::format("{} {:.6g} > {:.6g}", name, value, *limit));
}

}  // namespace

std::string sceneName(const std::string& scenePath) {
  constexpr std::string_view kBuiltin = "builtin:";
  if (scenePath.starts_with(kBuiltin)) return scenePath.substr(kBuiltin.size());
  return std::filesystem::path(scenePath).stem().string();
}

std::string deviceClass(const render::DeviceDescription& device) {
  if (device.type == "cpu") return "lavapipe";
  std::string out;
  bool dash = false;
  for (unsigned char c : device.name) {
    if (std::isalnum(c)) {
      out += static_cast<char>(std::tolower(c));
      dash = false;
    } else if (!dash && !out.empty()) {
      out += '-';
      dash = true;
    }
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "unknown-device" : out;
}

Thresholds thresholdsFromJson(const nlohmann::json& j, const std::filesystem::path& file, const std::string& where) {
  if (!j.is_object()) throw InputError(file.string() + ": field '" + where + "' must be an object");
  Thresholds t;
  t.flipMean = optionalLimit(j, "flip_mean", file, where);
  t.flipP99 = optionalLimit(j, "flip_p99", file, where);
  t.rmse = optionalLimit(j, "rmse", file, where);
  t.maxAbsError = optionalLimit(j, "max_abs_error", file, where);
  t.shareOverThreshold = optionalLimit(j, "share_over_threshold", file, where);
  t.psnrMin = optionalLimit(j, "psnr_min_db", file, where);
  t.channelThreshold = optionalLimit(j, "channel_threshold", file, where);
  return t;
}

nlohmann::json toJson(const Thresholds& t) {
  nlohmann::json j = nlohmann::json::object();
  auto put = [&](const char* key, const std::optional<double>& v) {
    if (v) j[key] = *v;
  };
  put("flip_mean", t.flipMean);
  put("flip_p99", t.flipP99);
  put("rmse", t.rmse);
  put("max_abs_error", t.maxAbsError);
  put("share_over_threshold", t.shareOverThreshold);
  put("psnr_min_db", t.psnrMin);
  put("channel_threshold", t.channelThreshold);
  return j;
}

Golden loadGolden(const std::filesystem::path& where) {
  std::error_code ec;
  const std::filesystem::path jsonPath =
      std::filesystem::is_directory(where, ec) ? where / (std::string(kDefaultGoldenConfig) + ".json") : where;
  if (!std::filesystem::is_regular_file(jsonPath, ec)) {
    throw InputError(jsonPath.string() + ": no golden here (create one with `fgbench bless SCENE`)");
  }
  Golden golden;
  golden.jsonPath = jsonPath;
  golden.document = readJsonFile(jsonPath);
  const auto& images = requireField(golden.document, "images", jsonPath);
  const std::filesystem::path dir = jsonPath.parent_path();
  golden.displayImage = dir / requireString(images, "display", jsonPath, "images");
  if (images.contains("hdr")) golden.hdrImage = dir / requireString(images, "hdr", jsonPath, "images");
  for (const auto& path : {golden.displayImage, golden.hdrImage}) {
    if (!path.empty() && !std::filesystem::is_regular_file(path, ec)) {
      throw InputError(jsonPath.string() + ": golden image " + path.string() + " is missing");
    }
  }
  if (golden.document.contains("config")) {
    const auto& c = golden.document["config"];
    golden.config.width = static_cast<uint32_t>(optionalNumber(c, "width", 0, jsonPath, "config"));
    golden.config.height = static_cast<uint32_t>(optionalNumber(c, "height", 0, jsonPath, "config"));
    golden.config.msaa = static_cast<uint32_t>(optionalNumber(c, "msaa", 0, jsonPath, "config"));
    golden.config.frames = static_cast<uint32_t>(optionalNumber(c, "frames", 0, jsonPath, "config"));
    golden.config.hasWarmup = c.contains("warmup");
    golden.config.warmup = static_cast<uint32_t>(optionalNumber(c, "warmup", 0, jsonPath, "config"));
    if (c.contains("knobs")) {
      for (const auto& [key, value] : c["knobs"].items()) {
        golden.config.knobs[key] = value.is_string() ? value.get<std::string>() : value.dump();
      }
    }
  }
  const auto& thresholds = requireField(golden.document, "thresholds", jsonPath);
  golden.display = thresholdsFromJson(requireField(thresholds, "display", jsonPath, "thresholds"), jsonPath, "thresholds.display");
  if (thresholds.contains("hdr")) golden.hdr = thresholdsFromJson(thresholds["hdr"], jsonPath, "thresholds.hdr");
  return golden;
}

MetricOptions metricOptionsFor(const Thresholds& limits) {
  MetricOptions options;
  if (limits.channelThreshold) options.channelThreshold = *limits.channelThreshold;
  return options;
}

ImageVerdict judgeImage(const std::string& kind, const ImageMetrics& m, const Thresholds& limits) {
  ImageVerdict verdict{kind, m, {}};
  if (m.nonFiniteReference) verdict.failures.push_back(fmt::format("{} NaN/Inf pixels in the golden", m.nonFiniteReference));
  if (m.nonFiniteTest) verdict.failures.push_back(fmt::format("{} NaN/Inf pixels in the render", m.nonFiniteTest));
  if (m.flip) {
    checkAbove(verdict.failures, "flip_mean", m.flip->mean, limits.flipMean);
    checkAbove(verdict.failures, "flip_p99", m.flip->p99, limits.flipP99);
  }
  checkAbove(verdict.failures, "rmse", m.rmse, limits.rmse);
  checkAbove(verdict.failures, "max_abs_error", m.maxAbsError, limits.maxAbsError);
  checkAbove(verdict.failures, "share_over_threshold", m.shareOverThreshold, limits.shareOverThreshold);
  if (limits.psnrMin && std::isfinite(m.psnr) && m.psnr < *limits.psnrMin) {
    verdict.failures.push_back(fmt::format("psnr {:.3f} dB < {:.3f} dB", m.psnr, *limits.psnrMin));
  }
  return verdict;
}

nlohmann::json toJson(const GoldenResult& result) {
  nlohmann::json metrics = nlohmann::json::object();
  for (const auto& image : result.images) {
    nlohmann::json entry = toJson(image.metrics);
    entry["failures"] = image.failures;
    metrics[image.kind] = std::move(entry);
  }
  nlohmann::json j{{"file", result.file}, {"verdict", result.verdict}, {"metrics", metrics}};
  if (!result.diffImage.empty()) j["diff_image"] = result.diffImage;
  return j;
}

Thresholds thresholdsFromNoise(const std::optional<ImageMetrics>& noise, bool hdr) {
  // Floors: what 8-bit (display) or half-float (HDR) rounding and tiny rasterisation differences
  // between drivers produce; multipliers: headroom over the run-to-run noise seen at bless time.
  constexpr double kNoiseHeadroom = 3.0;
  Thresholds t;
  auto limit = [&](double floor, double noiseValue) { return std::max(floor, kNoiseHeadroom * noiseValue); };
  const double flipMean = noise && noise->flip ? noise->flip->mean : 0.0;
  const double flipP99 = noise && noise->flip ? noise->flip->p99 : 0.0;
  t.flipMean = limit(0.01, flipMean);
  t.flipP99 = limit(0.15, flipP99);
  t.rmse = limit(hdr ? 0.02 : 0.01, noise ? noise->rmse : 0.0);
  t.shareOverThreshold = limit(0.01, noise ? noise->shareOverThreshold : 0.0);
  t.channelThreshold = hdr ? kDefaultLinearChannelThreshold * 5 : kDefaultSrgbChannelThreshold * 4;
  return t;
}

}  // namespace fgb::harness
