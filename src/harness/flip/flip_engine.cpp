// The strip-tiled FLIP engine. All filters are separable (the blue-yellow CSF is a sum of two
// separable Gaussians) and folded around their centre; kernels that read the same input share one
// pass over it. The image is cut into strips of columns, which the workers take one at a time and
// walk from top to bottom: each source row entering the vertical window is converted to YCxCz and
// filtered horizontally into per-plane rings of the last rows, the vertical filters produce four
// output rows at a time from the rings, and the colour transforms and the error follow on those
// rows. Nothing of the size of the image is written except the error map, and a strip's working set
// stays in the core's L2 cache. HDR-FLIP filters several exposures per sweep down a strip (one read
// of the input for all of them) and keeps the per-pixel maximum. The inner loops are written for
// 16-float vectors and compiled for AVX-512, AVX2 + FMA and the baseline instruction set, chosen at
// run time.
#include "flip_engine.hpp"

#include <fgb/harness/base/parallel.hpp>

#include "flip_filters.hpp"
#include "flip_model.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace fgb::harness::flip_detail {
namespace {

// Row lengths are padded to whole vectors.
constexpr int kBlock = kMaxVecLanes;
// Columns per strip. Its source rows are converted with r columns more on either side (which the
// horizontal filters read); the rings hold 2 images * 7 planes * (2r + 4) rows of the strip's width
// per exposure (~170 KB at 4K's default observer, r = 10).
constexpr uint32_t kStripWidth = 128;
// Source rows are prefetched this many rows ahead of the one being converted (the hardware
// prefetcher does not cross into the next row's strip segment; measured best of 0, 1, 2, 4).
constexpr int kPrefetchRows = 4;
// L2 cache that the rings of the exposures filtered in one sweep may take (per core, 1 MB or more
// on current x86 cores): three exposures at 4K's default observer.
constexpr std::size_t kRingBudget = 700 * 1024;

struct EngineKernels {
  // Horizontal CSF terms (the blue-yellow pair padded to one radius: one pass over Cz) and
  // vertical ones.
  FoldedKernel hAchromatic, hRedGreen, hBlueYellow1, hBlueYellow2;
  FoldedKernel vAchromatic, vRedGreen, vBlueYellow1, vBlueYellow2;
  FoldedKernel gauss, edge, point;  // feature kernels, the same along both axes, of one radius
  int radius = 0;                   // the largest radius of any of them
  // The achromatic CSF filters Y' = 116 Y - 16. It is applied to Y instead (horizontally in the
  // same pass as the feature kernels, which read Y too: hAchromatic is padded to their radius), as
  // Y' filtered = 116 (Y filtered) - 16 sum, sum = the sum of the 2D kernel's taps; what remains of
  // (Y' filtered + 16) / 116, the value the colour transform starts from, is 16 (1 - sum) / 116.
  float achromaticOffset = 0.0f;
};

EngineKernels foldKernels(const Kernels& k) {
  EngineKernels e;
  const int feature = std::max({k.gaussian.radius, k.edge.radius, k.point.radius});
  e.gauss = padTo(fold(k.gaussian), feature);
  e.edge = padTo(fold(k.edge), feature);
  e.point = padTo(fold(k.point), feature);
  if (e.edge.centre != 0.0f || !e.edge.odd || e.gauss.odd || e.point.odd) throw std::logic_error("FLIP: unexpected kernel parity");
  if (k.csfAchromatic.radius > feature) throw std::logic_error("FLIP: achromatic CSF wider than the feature kernels");
  e.hAchromatic = padTo(fold(k.csfAchromatic), feature);
  e.hRedGreen = fold(k.csfRedGreen);
  const int blueYellow = std::max(k.csfBlueYellow1.radius, k.csfBlueYellow2.radius);
  e.hBlueYellow1 = padTo(fold(k.csfBlueYellow1), blueYellow);
  e.hBlueYellow2 = padTo(fold(k.csfBlueYellow2), blueYellow);
  e.vAchromatic = fold(k.csfAchromaticV);
  e.vRedGreen = fold(k.csfRedGreenV);
  e.vBlueYellow1 = fold(k.csfBlueYellow1V);
  e.vBlueYellow2 = fold(k.csfBlueYellow2V);
  e.radius = std::max({feature, e.hRedGreen.radius, blueYellow, e.vAchromatic.radius, e.vRedGreen.radius, e.vBlueYellow1.radius,
                       e.vBlueYellow2.radius});
  e.achromaticOffset = static_cast<float>(16.0 * (1.0 - sumOf(k.csfAchromatic) * sumOf(k.csfAchromaticV)) / 116.0);
  return e;
}

// sRGB decoding by table with linear interpolation (error < 1e-6): the exact curve's powf per
// channel dominated LDR-FLIP's colour conversion.
class SrgbDecoder {
 public:
  SrgbDecoder() {
    for (int i = 0; i <= kSteps; ++i) table_[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<float>(i) / kSteps);
  }
  float operator()(float encoded) const {
    const float position = std::clamp(encoded, 0.0f, 1.0f) * kSteps;
    const int i = std::min(static_cast<int>(position), kSteps - 1);
    const float f = position - static_cast<float>(i);
    return table_[static_cast<std::size_t>(i)] + f * (table_[static_cast<std::size_t>(i) + 1] - table_[static_cast<std::size_t>(i)]);
  }

 private:
  static constexpr int kSteps = 4096;
  std::array<float, kSteps + 1> table_{};
};

const SrgbDecoder& srgbDecoder() {
  static const SrgbDecoder decoder;
  return decoder;
}

// The sources and what runEngine derives from them for the workers.
struct EngineInput : EngineSources {
  explicit EngineInput(EngineSources sources) : EngineSources(std::move(sources)) {}
  EngineKernels k;
  float cmax = 1.0f;
  uint32_t stripWidth = kStripWidth, strips = 1, bandHeight = 1, bands = 1;
  uint32_t group = 1;  // exposures filtered together per sweep down a strip
  float* map = nullptr;
};

// Output rows filtered vertically in one pass (see convolveRows).
constexpr int kRowsPerPass = 4;

enum Signal { SignalRed, SignalGreen, SignalBlue, SignalCx, SignalCz, SignalY, kSignals };
// Horizontally filtered planes kept in the rings: Y (achromatic CSF, feature Gaussian, edge and
// point kernels), Cx (red-green CSF), Cz (both blue-yellow terms).
enum Plane { PlaneAchromatic, PlaneGauss, PlaneEdge, PlanePoint, PlaneRedGreen, PlaneBlueYellow1, PlaneBlueYellow2, kPlanes };

struct EngineScratch {
  int radius, ringRows, group;
  int outWidth;     // output columns of a strip, rounded up to whole vectors
  int signalWidth;  // columns of the source signals: outWidth + 2 radius (the horizontal margins)
  std::vector<float> signals;   // [signal][column]: one source row, linear RGB and YCxCz at one exposure
  std::vector<float> ring;      // [exposure in group][image][plane][row % ringRows][column]
  std::vector<float> block;     // [output row of the pass][image][BlockValue][column]
  std::vector<float> rowError;  // [output row of the pass][column]: the error, maximum over the group's exposures
  std::vector<std::ptrdiff_t> rowOffsets, columnOffsets;

  explicit EngineScratch(const EngineInput& in)
      : radius(in.k.radius),
        ringRows(2 * in.k.radius + kRowsPerPass),  // the vertical windows of one pass
        group(static_cast<int>(in.group)),
        outWidth(roundUp(static_cast<int>(std::min(in.stripWidth, in.width)))),
        signalWidth(roundUp(outWidth + 2 * radius)),
        signals(static_cast<std::size_t>(kSignals) * static_cast<std::size_t>(signalWidth)),
        ring(static_cast<std::size_t>(group) * 2 * kPlanes * static_cast<std::size_t>(ringRows) * static_cast<std::size_t>(outWidth)),
        block(static_cast<std::size_t>(kRowsPerPass) * 2 * kPerImage * static_cast<std::size_t>(outWidth)),
        rowError(static_cast<std::size_t>(kRowsPerPass) * static_cast<std::size_t>(outWidth)),
        rowOffsets(static_cast<std::size_t>(ringRows)),
        columnOffsets(static_cast<std::size_t>(2 * radius + 1)) {
    for (std::size_t i = 0; i < columnOffsets.size(); ++i) columnOffsets[i] = static_cast<std::ptrdiff_t>(i);
  }

  static int roundUp(int n) { return (n + kBlock - 1) / kBlock * kBlock; }
  float* signal(int which) { return signals.data() + static_cast<std::size_t>(which) * static_cast<std::size_t>(signalWidth); }
  float* plane(int exposure, int image, int which) {
    return ring.data() + static_cast<std::size_t>((exposure * 2 + image) * kPlanes + which) * static_cast<std::size_t>(ringRows) *
                             static_cast<std::size_t>(outWidth);
  }
  // Per output row and image: filtered Y, Cx, the two Cz terms, the edge and point components;
  // then L, a, b.
  enum BlockValue { Y, Cx, Cz1, Cz2, Edge1, Edge2, Point1, Point2, L, A, B, kPerImage };
  float* blockValues(int row, int image, int value) {
    return block.data() + static_cast<std::size_t>((row * 2 + image) * kPerImage + value) * static_cast<std::size_t>(outWidth);
  }
  float* errors(int row) { return rowError.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(outWidth); }
};

// Linear RGB of source columns x0 .. x0 + count - 1 of one row, planar (clamped to the image: the
// replicated border of the paper's filters): display images decoded and clamped to [0, 1], HDR
// images with negative and non-finite values set to 0 (the exposure and tone mapping follow).
FGB_INLINE void loadRow(const EngineInput& in, int image, uint32_t row, int x0, int count, float* __restrict r, float* __restrict g,
                        float* __restrict b) {
  const int first = std::max(0, x0), end = std::min(static_cast<int>(in.width), x0 + count);
  const int offset = first - x0;
  const float* __restrict px = in.rgba[static_cast<std::size_t>(image)] + (static_cast<std::size_t>(row) * in.width + static_cast<std::size_t>(first)) * 4;
  const int n = end - first;
  if (in.toneMap) {
#pragma GCC ivdep
    for (int i = 0; i < n; ++i) {
      r[offset + i] = nonNegativeFinite(px[4 * i + 0]);
      g[offset + i] = nonNegativeFinite(px[4 * i + 1]);
      b[offset + i] = nonNegativeFinite(px[4 * i + 2]);
    }
  } else if (in.srgb[static_cast<std::size_t>(image)]) {
    const SrgbDecoder& decode = srgbDecoder();
    for (int i = 0; i < n; ++i) {
      r[offset + i] = decode(unitFinite(px[4 * i + 0]));
      g[offset + i] = decode(unitFinite(px[4 * i + 1]));
      b[offset + i] = decode(unitFinite(px[4 * i + 2]));
    }
  } else {
#pragma GCC ivdep
    for (int i = 0; i < n; ++i) {
      r[offset + i] = unitFinite(px[4 * i + 0]);
      g[offset + i] = unitFinite(px[4 * i + 1]);
      b[offset + i] = unitFinite(px[4 * i + 2]);
    }
  }
  for (float* channel : {r, g, b}) {
    std::fill(channel, channel + offset, channel[offset]);
    std::fill(channel + offset + n, channel + count, channel[offset + n - 1]);
  }
}

// Cx, Cz and Y of YCxCz from a row of linear RGB (HDR: ACES-tone-mapped at an exposure scale first).
FGB_INLINE void opponentRow(const float* __restrict r, const float* __restrict g, const float* __restrict b, int count, bool toneMap,
                            float scale, float* __restrict cx, float* __restrict cz, float* __restrict yn) {
  constexpr float invXn = 1.0f / kXn, invZn = 1.0f / kZn;
  auto opponent = [&](int i, float red, float green, float blue) FGB_LAMBDA_INLINE {
    const float x = 0.41238656f * red + 0.35759149f * green + 0.18045049f * blue;
    const float y = 0.21263682f * red + 0.71518298f * green + 0.07218020f * blue;
    const float z = 0.01933062f * red + 0.11919716f * green + 0.95037259f * blue;
    cx[i] = 500.0f * (x * invXn - y);
    cz[i] = 200.0f * (y - z * invZn);
    yn[i] = y;  // = (Y' + 16) / 116 of YCxCz, and the luminance the features filter
  };
  if (toneMap) {
#pragma GCC ivdep
    for (int i = 0; i < count; ++i) opponent(i, acesCurveFloat(r[i] * scale), acesCurveFloat(g[i] * scale), acesCurveFloat(b[i] * scale));
  } else {
#pragma GCC ivdep
    for (int i = 0; i < count; ++i) opponent(i, r[i], g[i], b[i]);
  }
}

FGB_INLINE void perceptualRow(EngineScratch& s, int row, int image, int n, float achromaticOffset) {
  const float* __restrict y = s.blockValues(row, image, EngineScratch::Y);
  const float* __restrict cx = s.blockValues(row, image, EngineScratch::Cx);
  const float* __restrict cz1 = s.blockValues(row, image, EngineScratch::Cz1);
  const float* __restrict cz2 = s.blockValues(row, image, EngineScratch::Cz2);
  float* __restrict outL = s.blockValues(row, image, EngineScratch::L);
  float* __restrict outA = s.blockValues(row, image, EngineScratch::A);
  float* __restrict outB = s.blockValues(row, image, EngineScratch::B);
  constexpr std::array<float, 9> m = kPerceptual.toRgb;
  constexpr std::array<float, 9> w = kPerceptual.toXyz;
#pragma GCC ivdep
  for (int x = 0; x < n; ++x) {
    const float yy = y[x] + achromaticOffset;  // (Y' + 16) / 116 of the filtered Y'
    const float cxx = cx[x], czz = cz1[x] + cz2[x];
    const float r = clamp01(m[0] * yy + m[1] * cxx + m[2] * czz);
    const float g = clamp01(m[3] * yy + m[4] * cxx + m[5] * czz);
    const float b = clamp01(m[6] * yy + m[7] * cxx + m[8] * czz);
    const float fx = labFunction(w[0] * r + w[1] * g + w[2] * b);
    const float fy = labFunction(w[3] * r + w[4] * g + w[5] * b);
    const float fz = labFunction(w[6] * r + w[7] * g + w[8] * b);
    const float l = 116.0f * fy - 16.0f;
    outL[x] = l;
    outA[x] = 5.0f * l * (fx - fy);  // 0.01 L * 500 (fx - fy)
    outB[x] = 2.0f * l * (fy - fz);  // 0.01 L * 200 (fy - fz)
  }
}

// HyAB colour error, redistributed; feature error; combined dE_c^(1 - dE_f); the maximum with the
// exposures before (First: the first exposure of the group).
template <bool First>
FGB_INLINE void errorRow(EngineScratch& s, int row, float cmax, int n) {
  const auto qc = static_cast<float>(kColorExponent);
  static_assert(kFeatureExponent == 0.5, "the feature exponent is applied as a square root");
  auto value = [&](int image, int which) { return s.blockValues(row, image, which); };
  const float* __restrict rl = value(0, EngineScratch::L);
  const float* __restrict ra = value(0, EngineScratch::A);
  const float* __restrict rb = value(0, EngineScratch::B);
  const float* __restrict tl = value(1, EngineScratch::L);
  const float* __restrict ta = value(1, EngineScratch::A);
  const float* __restrict tb = value(1, EngineScratch::B);
  const float* __restrict re1 = value(0, EngineScratch::Edge1);
  const float* __restrict re2 = value(0, EngineScratch::Edge2);
  const float* __restrict rp1 = value(0, EngineScratch::Point1);
  const float* __restrict rp2 = value(0, EngineScratch::Point2);
  const float* __restrict te1 = value(1, EngineScratch::Edge1);
  const float* __restrict te2 = value(1, EngineScratch::Edge2);
  const float* __restrict tp1 = value(1, EngineScratch::Point1);
  const float* __restrict tp2 = value(1, EngineScratch::Point2);
  float* __restrict out = s.errors(row);
#pragma GCC ivdep
  for (int x = 0; x < n; ++x) {
    const float da = ra[x] - ta[x], db = rb[x] - tb[x];
    const float hy = std::abs(rl[x] - tl[x]) + std::sqrt(da * da + db * db);
    const float colorError = redistributeColorError(fastPow(hy, qc), cmax);
    const float refEdge = std::sqrt(re1[x] * re1[x] + re2[x] * re2[x]);
    const float refPoint = std::sqrt(rp1[x] * rp1[x] + rp2[x] * rp2[x]);
    const float testEdge = std::sqrt(te1[x] * te1[x] + te2[x] * te2[x]);
    const float testPoint = std::sqrt(tp1[x] * tp1[x] + tp2[x] * tp2[x]);
    const float featureDifference = std::max(std::abs(refEdge - testEdge), std::abs(refPoint - testPoint));
    const float featureError = clamp01(std::sqrt(featureDifference * (1.0f / std::numbers::sqrt2_v<float>)));
    const float error = std::min(1.0f, fastPow(colorError, 1.0f - featureError));
    if constexpr (First) {
      out[x] = error;
    } else {
      out[x] = std::max(out[x], error);
    }
  }
}

// One tile (a strip of columns, a band of rows) of the error map, over every exposure.
// Each source row that enters the vertical window is converted (for every exposure of the group,
// from one read of the input) to YCxCz and filtered horizontally into rings of 7 planes per image
// and exposure; the vertical filters then run on the rings for kRowsPerPass output rows at once, and
// the colour transforms and the error on the rows they produce. All of it stays in L1 and L2.
template <int L, int NV, int NVRows, int QRows>
FGB_INLINE void processTile(const EngineInput& in, uint32_t tile, EngineScratch& s) {
  static_assert(QRows <= kRowsPerPass);
  const EngineKernels& k = in.k;
  const int R = s.radius;
  const uint32_t strip = tile % in.strips, band = tile / in.strips;
  const uint32_t x0 = strip * in.stripWidth;
  const int width = static_cast<int>(std::min(in.stripWidth, in.width - x0));
  const int outWidth = EngineScratch::roundUp(width);
  const int stride = s.outWidth;
  const uint32_t y0 = band * in.bandHeight, y1 = std::min(in.height, y0 + in.bandHeight);
  const int lastRow = static_cast<int>(in.height) - 1;
  const std::ptrdiff_t* columns = s.columnOffsets.data();
  const auto exposures = static_cast<int>(in.scales.size());
  const int firstColumn = std::max(0, static_cast<int>(x0) - R);
  const int prefetchPixels = std::min(outWidth + 2 * R, static_cast<int>(in.width) - firstColumn);
  const FoldedKernel* const achromatic[1] = {&k.vAchromatic};
  const FoldedKernel* const redGreen[1] = {&k.vRedGreen};
  const FoldedKernel* const blueYellow1[1] = {&k.vBlueYellow1};
  const FoldedKernel* const blueYellow2[1] = {&k.vBlueYellow2};
  const FoldedKernel* const gauss[1] = {&k.gauss};
  const FoldedKernel* const edgeAndPoint[2] = {&k.edge, &k.point};
  float* const red = s.signal(SignalRed);
  float* const green = s.signal(SignalGreen);
  float* const blue = s.signal(SignalBlue);
  float* const cx = s.signal(SignalCx);
  float* const cz = s.signal(SignalCz);
  float* const yn = s.signal(SignalY);

  for (int g0 = 0; g0 < exposures; g0 += s.group) {
    const int g1 = std::min(exposures, g0 + s.group);
    int next = std::max(0, static_cast<int>(y0) - R);  // the next source row to filter horizontally
    for (uint32_t y = y0; y < y1; y += QRows) {
      const int rowsHere = static_cast<int>(std::min<uint32_t>(QRows, y1 - y));
      for (const int last = std::min(lastRow, static_cast<int>(y) + QRows - 1 + R); next <= last; ++next) {
        const std::ptrdiff_t slot = static_cast<std::ptrdiff_t>(next % s.ringRows) * stride;
        for (int image = 0; image < 2; ++image) {
          if (next + kPrefetchRows <= lastRow) {  // a later row: its cache lines arrive while these rows are filtered
            const float* ahead = in.rgba[static_cast<std::size_t>(image)] +
                                 (static_cast<std::size_t>(next + kPrefetchRows) * in.width + static_cast<std::size_t>(firstColumn)) * 4;
            for (int i = 0; i < prefetchPixels * 4; i += 16) __builtin_prefetch(ahead + i);
          }
          loadRow(in, image, static_cast<uint32_t>(next), static_cast<int>(x0) - R, outWidth + 2 * R, red, green, blue);
          for (int e = g0; e < g1; ++e) {
            opponentRow(red, green, blue, outWidth + 2 * R, in.toneMap, in.scales[static_cast<std::size_t>(e)], cx, cz, yn);
            auto plane = [&](int which) { return s.plane(e - g0, image, which) + slot; };
            // Output column x reads signal[R + x + j - r] for tap j of a radius-r kernel.
            convolveFeatures<L, NV>(yn + R - k.gauss.radius, columns, k.gauss, k.edge, k.point, k.hAchromatic,
                                              plane(PlaneGauss), plane(PlaneEdge), plane(PlanePoint), plane(PlaneAchromatic), outWidth);
            convolve1<L, NV>(cx + R - k.hRedGreen.radius, columns, k.hRedGreen, plane(PlaneRedGreen), outWidth);
            convolve2<L, NV>(cz + R - k.hBlueYellow1.radius, columns, k.hBlueYellow1, k.hBlueYellow2,
                                       plane(PlaneBlueYellow1), plane(PlaneBlueYellow2), outWidth);
          }
        }
      }
      // Window entry i is input row clamp(y + i - R), wherever the ring keeps it.
      for (int i = 0; i < s.ringRows; ++i) {
        const int row = std::clamp(static_cast<int>(y) + i - R, 0, lastRow);
        s.rowOffsets[static_cast<std::size_t>(i)] = static_cast<std::ptrdiff_t>(row % s.ringRows) * stride;
      }
      const std::ptrdiff_t* rows = s.rowOffsets.data();
      for (int e = g0; e < g1; ++e) {
        for (int image = 0; image < 2; ++image) {
          // Kernel j of `kernels` on `plane`, into block value values[j] of each output row.
          auto vertical = [&]<int K, unsigned OddMask>(int plane, const FoldedKernel* const* kernels,
                                                       const std::array<int, K>& values) FGB_LAMBDA_INLINE {
            float* out[QRows * K];
            for (int q = 0; q < QRows; ++q) {
              for (int j = 0; j < K; ++j) out[q * K + j] = s.blockValues(q, image, values[static_cast<std::size_t>(j)]);
            }
            convolveRows<L, NVRows, QRows, K, OddMask>(s.plane(e - g0, image, plane), rows + (R - kernels[0]->radius), kernels,
                                                                 out, outWidth);
          };
          vertical.template operator()<1, 0>(PlaneAchromatic, achromatic, {EngineScratch::Y});
          vertical.template operator()<1, 0>(PlaneRedGreen, redGreen, {EngineScratch::Cx});
          vertical.template operator()<1, 0>(PlaneBlueYellow1, blueYellow1, {EngineScratch::Cz1});
          vertical.template operator()<1, 0>(PlaneBlueYellow2, blueYellow2, {EngineScratch::Cz2});
          // Edge = (E * g, G * e) and point = (P * g, G * p) along y.
          vertical.template operator()<1, 0>(PlaneEdge, gauss, {EngineScratch::Edge1});
          vertical.template operator()<1, 0>(PlanePoint, gauss, {EngineScratch::Point1});
          vertical.template operator()<2, 1>(PlaneGauss, edgeAndPoint, {EngineScratch::Edge2, EngineScratch::Point2});
        }
        for (int q = 0; q < rowsHere; ++q) {
          perceptualRow(s, q, 0, outWidth, k.achromaticOffset);
          perceptualRow(s, q, 1, outWidth, k.achromaticOffset);
          if (e == g0) {
            errorRow<true>(s, q, in.cmax, outWidth);
          } else {
            errorRow<false>(s, q, in.cmax, outWidth);
          }
        }
      }
      for (int q = 0; q < rowsHere; ++q) {
        const float* __restrict rowError = s.errors(q);
        float* __restrict out = in.map + static_cast<std::size_t>(y + static_cast<uint32_t>(q)) * in.width + x0;
        if (g0 == 0) {
          std::copy(rowError, rowError + width, out);
        } else {
#pragma GCC ivdep
          for (int x = 0; x < width; ++x) out[x] = std::max(out[x], rowError[x]);
        }
      }
    }
  }
}

using TileFunction = void (*)(const EngineInput&, uint32_t, EngineScratch&);

// Vector width (floats), vectors per step of the horizontal and the vertical filters, output rows
// per vertical pass: as many accumulators as the ISA has registers for.
void tileBaseline(const EngineInput& in, uint32_t tile, EngineScratch& s) { processTile<4, 2, 1, 2>(in, tile, s); }
#if FGB_X86_DISPATCH
__attribute__((target("arch=x86-64-v3"))) void tileAvx2(const EngineInput& in, uint32_t tile, EngineScratch& s) {
  processTile<8, 2, 1, 2>(in, tile, s);
}
__attribute__((target("arch=x86-64-v4,prefer-vector-width=512"))) void tileAvx512(const EngineInput& in, uint32_t tile,
                                                                                   EngineScratch& s) {
  processTile<16, 4, 1, 4>(in, tile, s);
}
#endif

// The widest instruction set the CPU has; FGBENCH_FLIP_ISA=baseline|avx2 caps it (for tests and
// for comparing the variants).
TileFunction selectTileFunction() {
  const char* cap = std::getenv("FGBENCH_FLIP_ISA");
  const std::string_view limit = cap ? cap : "";
  if (limit == "baseline") return tileBaseline;
#if FGB_X86_DISPATCH
  __builtin_cpu_init();
  const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2") &&
                  __builtin_cpu_supports("f16c") && __builtin_cpu_supports("movbe");
  const bool v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                  __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd");
  if (v4 && limit != "avx2") return tileAvx512;
  if (v3) return tileAvx2;
#endif
  return tileBaseline;
}

}  // namespace

FlipMap runEngine(EngineSources sources, double ppd) {
  EngineInput in(std::move(sources));
  in.k = foldKernels(makeKernels(ppd));
  in.cmax = maxColorDifference();
  (void)srgbDecoder();  // built before the workers start
  FlipMap map{in.width, in.height, zeroFilledBuffer(static_cast<std::size_t>(in.width) * in.height)};
  in.map = map.error.data();
  const unsigned workers = workerCount();
  in.stripWidth = std::min(kStripWidth, in.width);
  in.strips = (in.width + in.stripWidth - 1) / in.stripWidth;
  // Enough tiles that workers finishing at different times wait little for each other; bands of
  // rows (each re-filtering 2r rows of its neighbours) only where there are few strips.
  const uint32_t wanted = 8 * workers;
  const uint32_t maxBands = std::max(1u, in.height / static_cast<uint32_t>(8 * in.k.radius + 8));
  in.bands = std::clamp((wanted + in.strips - 1) / in.strips, 1u, maxBands);
  in.bandHeight = (in.height + in.bands - 1) / in.bands;
  in.bands = (in.height + in.bandHeight - 1) / in.bandHeight;
  // Exposures per sweep: as many as the L2 budget takes, in groups of equal size.
  const auto ringWidth = static_cast<std::size_t>(EngineScratch::roundUp(static_cast<int>(in.stripWidth)));
  const std::size_t ringBytes = 2 * kPlanes * static_cast<std::size_t>(2 * in.k.radius + kRowsPerPass) * ringWidth * sizeof(float);
  const std::size_t maxGroup = std::max<std::size_t>(1, kRingBudget / ringBytes);
  const std::size_t groups = (in.scales.size() + maxGroup - 1) / maxGroup;
  in.group = static_cast<uint32_t>((in.scales.size() + groups - 1) / groups);
  const uint32_t tiles = in.strips * in.bands;
  const TileFunction tileFunction = selectTileFunction();
  std::atomic<uint32_t> nextTile{0};
  parallelFor(std::min<std::size_t>(workers, tiles), 1, [&](std::size_t, std::size_t) {
    EngineScratch scratch(in);
    for (uint32_t tile = nextTile++; tile < tiles; tile = nextTile++) tileFunction(in, tile, scratch);
  });
  return map;
}

}  // namespace fgb::harness::flip_detail
