#include <fgb/harness/metrics.hpp>

#include <fgb/harness/parallel.hpp>
#include <fgb/harness/stats.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace fgb::harness {
namespace {

struct PixelTotals {
  double squaredError = 0.0;
  double maxAbs = 0.0;
  uint64_t finiteChannels = 0;
  uint64_t overThreshold = 0;
  uint64_t nonFiniteReference = 0, nonFiniteTest = 0;
  double referencePeak = 0.0;

  void add(const PixelTotals& o) {
    squaredError += o.squaredError;
    maxAbs = std::max(maxAbs, o.maxAbs);
    finiteChannels += o.finiteChannels;
    overThreshold += o.overThreshold;
    nonFiniteReference += o.nonFiniteReference;
    nonFiniteTest += o.nonFiniteTest;
    referencePeak = std::max(referencePeak, o.referencePeak);
  }
};

bool pixelFinite(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// Differences over RGB (alpha is not part of a rendered frame's appearance). Pixels where either
// image is non-finite are counted and excluded from the error statistics.
PixelTotals accumulateRange(const Image& ref, const Image& test, double threshold, std::size_t begin, std::size_t end,
                            std::vector<float>& absMap, std::vector<uint8_t>& mask) {
  PixelTotals t;
  for (std::size_t i = begin; i < end; ++i) {
    const float* a = &ref.rgba[i * 4];
    const float* b = &test.rgba[i * 4];
    const bool finiteA = pixelFinite(a), finiteB = pixelFinite(b);
    t.nonFiniteReference += finiteA ? 0 : 1;
    t.nonFiniteTest += finiteB ? 0 : 1;
    if (!finiteA || !finiteB) {
      mask[i] = 1;
      continue;
    }
    double pixelMax = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(static_cast<double>(a[c]) - b[c]);
      t.squaredError += d * d;
      pixelMax = std::max(pixelMax, d);
      t.referencePeak = std::max(t.referencePeak, static_cast<double>(a[c]));
    }
    t.finiteChannels += 3;
    t.maxAbs = std::max(t.maxAbs, pixelMax);
    if (pixelMax > threshold) ++t.overThreshold;
    absMap[i] = static_cast<float>(pixelMax);
  }
  return t;
}

PixelTotals accumulate(const Image& ref, const Image& test, double threshold, std::vector<float>& absMap, std::vector<uint8_t>& mask) {
  PixelTotals total;
  std::mutex totalMutex;
  parallelFor(ref.pixelCount(), 1 << 16, [&](std::size_t begin, std::size_t end) {
    const PixelTotals part = accumulateRange(ref, test, threshold, begin, end, absMap, mask);
    std::lock_guard lock(totalMutex);
    total.add(part);
  });
  return total;
}

void fillErrorStatistics(ImageMetrics& m, const PixelTotals& t, std::size_t pixels) {
  m.nonFiniteReference = t.nonFiniteReference;
  m.nonFiniteTest = t.nonFiniteTest;
  m.maxAbsError = t.maxAbs;
  const double mse = t.finiteChannels ? t.squaredError / static_cast<double>(t.finiteChannels) : 0.0;
  m.rmse = std::sqrt(mse);
  m.peak = m.domain == "srgb" ? 1.0 : std::max(1.0, t.referencePeak);
  m.psnr = mse > 0.0 ? 10.0 * std::log10(m.peak * m.peak / mse) : std::numeric_limits<double>::infinity();
  m.shareOverThreshold = pixels ? static_cast<double>(t.overThreshold) / static_cast<double>(pixels) : 0.0;
}

}  // namespace

FlipStatistics summarizeFlip(const std::vector<float>& errors, std::string mode) {
  FlipStatistics s;
  s.mode = std::move(mode);
  if (errors.empty()) return s;
  std::vector<double> values(errors.begin(), errors.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  // Exact percentiles with the same interpolation as summarize(), via selection rather than a sort.
  auto percentile = [&](double p) {
    const double position = p / 100.0 * static_cast<double>(values.size() - 1);
    const auto lower = static_cast<std::size_t>(position);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(lower), values.end());
    const double low = values[lower];
    if (lower + 1 >= values.size()) return low;
    const double high = *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(lower) + 1, values.end());
    return low + (high - low) * (position - static_cast<double>(lower));
  };
  s.p50 = percentile(50.0);
  s.p95 = percentile(95.0);
  s.p99 = percentile(99.0);
  s.max = *std::max_element(values.begin(), values.end());
  return s;
}

Comparison compareImages(const Image& reference, const Image& test, const MetricOptions& options) {
  if (reference.width != test.width || reference.height != test.height) {
    throw std::invalid_argument("image sizes differ: " + describeSize(reference) + " vs " + describeSize(test));
  }
  const bool srgb = reference.encoding == Encoding::Srgb || test.encoding == Encoding::Srgb;
  const Encoding domain = srgb ? Encoding::Srgb : Encoding::Linear;
  const Image ref = toEncoding(reference, domain);
  const Image tst = toEncoding(test, domain);

  Comparison result;
  ImageMetrics& m = result.metrics;
  m.width = ref.width;
  m.height = ref.height;
  m.domain = srgb ? "srgb" : "linear";
  m.channelThreshold = options.channelThreshold >= 0.0
                           ? options.channelThreshold
                           : (srgb ? kDefaultSrgbChannelThreshold : kDefaultLinearChannelThreshold);
  std::vector<float> absMap(ref.pixelCount(), 0.0f);
  result.nonFiniteMask.assign(ref.pixelCount(), 0);
  const PixelTotals totals = accumulate(ref, tst, m.channelThreshold, absMap, result.nonFiniteMask);
  fillErrorStatistics(m, totals, ref.pixelCount());

  if (options.flip && ref.pixelCount() > 0) {
    if (srgb) {
      FlipMap map = ldrFlip(ref, tst, options.pixelsPerDegree);
      m.flip = summarizeFlip(map.error, "ldr");
      result.errorMap = std::move(map.error);
    } else {
      HdrFlipResult hdr = hdrFlip(ref, tst, options.pixelsPerDegree);
      m.flip = summarizeFlip(hdr.map.error, "hdr");
      m.flip->startExposure = hdr.startExposure;
      m.flip->stopExposure = hdr.stopExposure;
      m.flip->exposures = hdr.exposures;
      result.errorMap = std::move(hdr.map.error);
    }
  } else {
    const float scaleBy = m.maxAbsError > 0.0 ? static_cast<float>(1.0 / m.maxAbsError) : 0.0f;
    for (float& v : absMap) v *= scaleBy;
    result.errorMap = std::move(absMap);
  }
  return result;
}

nlohmann::json toJson(const ImageMetrics& m) {
  nlohmann::json j;
  j["width"] = m.width;
  j["height"] = m.height;
  j["domain"] = m.domain;
  j["max_abs_error"] = m.maxAbsError;
  j["rmse"] = m.rmse;
  j["psnr_db"] = std::isfinite(m.psnr) ? nlohmann::json(m.psnr) : nlohmann::json(nullptr);
  j["psnr_peak"] = m.peak;
  j["channel_threshold"] = m.channelThreshold;
  j["share_over_threshold"] = m.shareOverThreshold;
  j["non_finite_reference"] = m.nonFiniteReference;
  j["non_finite_test"] = m.nonFiniteTest;
  if (m.flip) {
    nlohmann::json f{{"mode", m.flip->mode}, {"mean", m.flip->mean}, {"p50", m.flip->p50},
                     {"p95", m.flip->p95}, {"p99", m.flip->p99}, {"max", m.flip->max}};
    if (m.flip->mode == "hdr") {
      f["start_exposure"] = m.flip->startExposure;
      f["stop_exposure"] = m.flip->stopExposure;
      f["exposures"] = m.flip->exposures;
    }
    j["flip"] = f;
  }
  return j;
}

}  // namespace fgb::harness
