// Pieces of the self-contained HTML reports (sweep.html, stress.html): images as data: URIs and a
// log10 axis for inline SVG charts.
#pragma once

#include <cstdint>
#include <fgb/harness/image/image.hpp>
#include <string>
#include <span>
#include <vector>

namespace fgb::harness {

std::string base64(std::span<const uint8_t> bytes);
std::string pngDataUri(std::span<const uint8_t> png);  // "data:image/png;base64,..."

// <img> of `image` shrunk to at most `maxWidth` pixels wide, as an inline PNG.
inline constexpr uint32_t kThumbnailWidth = 420;  // pages show images at most this wide
std::string imgTag(const Image& image, const std::string& alt, uint32_t maxWidth = kThumbnailWidth);

// A log10 axis over [lo, hi]: position of a value and tick values (1, 2, 5 x 10^k inside the range).
struct LogAxis {
  double lo, hi;
  double at(double v, double from, double to) const;
  std::vector<double> ticks() const;
  std::vector<double> minorTicks() const;  // 3, 4, 6, 7, 8, 9 x 10^k inside the range: unlabelled grid lines
};

// At least a factor 1.5 across, centred on the data, so close points do not fill the whole plot;
// widened where needed so that at least two 1-2-5 ticks fall inside.
LogAxis paddedLogAxis(double lo, double hi);

// A tick value in plain decimals, 3 significant digits, never an exponent: "0.0005", "2.5", "380".
std::string tickLabel(double v);
// A duration given in ms, with its unit and `significant` digits (2: "2.4 s", "380 ms", "0.9 ms",
// "50 µs"; more digits show only where the value has them: 2 s stays "2 s").
std::string durationLabel(double ms, int significant = 2);

}  // namespace fgb::harness
