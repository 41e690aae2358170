// Pieces of the self-contained HTML reports (sweep.html, stress.html): images as data: URIs (with
// base64 from report.hpp) and a log10 axis for inline SVG charts.
#pragma once

#include <cstdint>
#include <fgb/harness/image.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::harness {

// <img> of `image` shrunk to at most `maxWidth` pixels wide, as an inline PNG.
std::string imgTag(const Image& image, const std::string& alt, uint32_t maxWidth = 420);

// A log10 axis over [lo, hi]: position of a value and tick values (1, 2, 5 x 10^k inside the range,
// or the ends when the range holds fewer than two of those).
struct LogAxis {
  double lo, hi;
  double at(double v, double from, double to) const;
  std::vector<double> ticks() const;
};

// At least a factor 1.5 across, centred on the data, so close points do not fill the whole plot.
LogAxis paddedLogAxis(double lo, double hi);

std::string tickLabel(double v);

}  // namespace fgb::harness
