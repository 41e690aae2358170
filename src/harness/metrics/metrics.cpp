#include <fgb/harness/metrics/metrics.hpp>

#include <fgb/harness/base/parallel.hpp>
#include <fgb/harness/stats/order_statistics.hpp>
#include <fgb/harness/stats/stats.hpp>

#include <algorithm>
#include <array>
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
// image is non-finite are counted and excluded from the error statistics. Four pixels at a time
// with separate sums (the double additions' latency bounded the single-sum loop).
PixelTotals accumulateRange(const Image& ref, const Image& test, double threshold, std::size_t begin, std::size_t end,
                            float* absMap, std::vector<uint8_t>& mask) {
  constexpr std::size_t kLanes = 4;
  std::array<double, kLanes> squared{}, maxAbs{}, peak{};
  std::array<uint64_t, kLanes> over{}, badReference{}, badTest{};
  uint64_t finitePixels = 0;
  for (std::size_t block = begin; block < end; block += kLanes) {
    const std::size_t lanes = std::min(kLanes, end - block);
    for (std::size_t lane = 0; lane < lanes; ++lane) {
      const std::size_t i = block + lane;
      const float* a = &ref.rgba[i * 4];
      const float* b = &test.rgba[i * 4];
      const bool finiteA = pixelFinite(a), finiteB = pixelFinite(b);
      badReference[lane] += finiteA ? 0 : 1;
      badTest[lane] += finiteB ? 0 : 1;
      if (!finiteA || !finiteB) {
        mask[i] = 1;
        continue;
      }
      const double d0 = std::abs(static_cast<double>(a[0]) - b[0]);
      const double d1 = std::abs(static_cast<double>(a[1]) - b[1]);
      const double d2 = std::abs(static_cast<double>(a[2]) - b[2]);
      squared[lane] += d0 * d0 + d1 * d1 + d2 * d2;
      const double pixelMax = std::max(d0, std::max(d1, d2));
      peak[lane] = std::max(peak[lane], static_cast<double>(std::max(a[0], std::max(a[1], a[2]))));
      maxAbs[lane] = std::max(maxAbs[lane], pixelMax);
      over[lane] += pixelMax > threshold ? 1 : 0;
      ++finitePixels;
      if (absMap) absMap[i] = static_cast<float>(pixelMax);
    }
  }
  PixelTotals t;
  for (std::size_t lane = 0; lane < kLanes; ++lane) {
    t.squaredError += squared[lane];
    t.maxAbs = std::max(t.maxAbs, maxAbs[lane]);
    t.referencePeak = std::max(t.referencePeak, peak[lane]);
    t.overThreshold += over[lane];
    t.nonFiniteReference += badReference[lane];
    t.nonFiniteTest += badTest[lane];
  }
  t.finiteChannels = 3 * finitePixels;
  return t;
}

// absMap (optional): max abs channel error per pixel.
PixelTotals accumulate(const Image& ref, const Image& test, double threshold, float* absMap, std::vector<uint8_t>& mask) {
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
  const std::size_t n = errors.size();
  std::mutex sumMutex;
  double sum = 0.0;
  parallelFor(n, 1 << 16, [&](std::size_t begin, std::size_t end) {
    double part = 0.0;
    for (std::size_t i = begin; i < end; ++i) part += static_cast<double>(errors[i]);
    std::lock_guard lock(sumMutex);
    sum += part;
  });
  s.mean = sum / static_cast<double>(n);
  // Exact percentiles with the same interpolation as summarize(): the order statistics at and just
  // above each position, found by radix selection instead of a sort.
  const std::array<double, 3> percents{50.0, 95.0, 99.0};
  std::vector<std::size_t> ranks;
  for (double p : percents) {
    const auto lower = static_cast<std::size_t>(p / 100.0 * static_cast<double>(n - 1));
    ranks.push_back(lower);
    ranks.push_back(std::min(lower + 1, n - 1));
  }
  ranks.push_back(n - 1);
  const float* data = errors.data();
  const std::vector<uint32_t> keys = detail::selectOrderKeys(
      n,
      [data](std::size_t begin, std::size_t end, uint32_t* out) {
        for (std::size_t i = begin; i < end; ++i) out[i - begin] = detail::orderKey(data[i]);
      },
      ranks);
  auto percentile = [&](std::size_t index) {
    const double position = percents[index] / 100.0 * static_cast<double>(n - 1);
    const auto lower = static_cast<std::size_t>(position);
    const double low = detail::fromOrderKey(keys[2 * index]);
    if (lower + 1 >= n) return low;
    const double high = detail::fromOrderKey(keys[2 * index + 1]);
    return low + (high - low) * (position - static_cast<double>(lower));
  };
  s.p50 = percentile(0);
  s.p95 = percentile(1);
  s.p99 = percentile(2);
  s.max = detail::fromOrderKey(keys.back());
  return s;
}

Comparison compareImages(const Image& reference, const Image& test, const MetricOptions& options) {
  if (reference.width != test.width || reference.height != test.height) {
    throw std::invalid_argument("image sizes differ: " + describeSize(reference) + " vs " + describeSize(test));
  }
  const bool srgb = reference.encoding == Encoding::Srgb || test.encoding == Encoding::Srgb;
  const Encoding domain = srgb ? Encoding::Srgb : Encoding::Linear;
  // Re-encoded copies only where needed (a 4K image is 133 MB).
  Image converted[2];
  if (reference.encoding != domain) converted[0] = toEncoding(reference, domain);
  if (test.encoding != domain) converted[1] = toEncoding(test, domain);
  const Image& ref = reference.encoding == domain ? reference : converted[0];
  const Image& tst = test.encoding == domain ? test : converted[1];

  Comparison result;
  ImageMetrics& m = result.metrics;
  m.width = ref.width;
  m.height = ref.height;
  m.domain = srgb ? "srgb" : "linear";
  m.channelThreshold = options.channelThreshold >= 0.0
                           ? options.channelThreshold
                           : (srgb ? kDefaultSrgbChannelThreshold : kDefaultLinearChannelThreshold);
  const bool flip = options.flip && ref.pixelCount() > 0;
  std::vector<float> absMap;  // the error map without FLIP
  if (!flip) absMap = zeroFilledBuffer(ref.pixelCount());
  result.nonFiniteMask = zeroFilledBytes(ref.pixelCount());
  const PixelTotals totals = accumulate(ref, tst, m.channelThreshold, flip ? nullptr : absMap.data(), result.nonFiniteMask);
  fillErrorStatistics(m, totals, ref.pixelCount());

  if (flip) {
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
