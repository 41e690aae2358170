// Pieces shared by the report's inline SVG charts (svg_charts.cpp, svg_timeline.cpp).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fgb/harness/report/report.hpp>
#include <string>

namespace fgb::harness::svg {

inline constexpr int kChartWidth = 760;
inline constexpr int kLabelWidth = 190;
inline constexpr int kRowHeight = 22;

// `id` lets the browser test find the chart (tests/report).
inline std::string open(int width, int height, const std::string& id, const std::string& title) {
  return fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" id="{3}" width="{0}" height="{1}" viewBox="0 0 {0} {1}" role="img" aria-label="{2}" font-family="sans-serif" font-size="12">)"
      "\n<title>{2}</title>\n",
      width, height, escapeXml(title), id);
}

inline std::string queueColor(const std::string& queue) {
  if (queue == "compute") return "#e08a2e";
  if (queue == "transfer") return "#4a9c5d";
  return "#3f6fb5";  // graphics
}

// A tick step of 1, 2 or 5 times a power of ten giving about five ticks over [0, max].
inline double niceStep(double max) {
  const double raw = std::max(max, 1e-9) / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (raw <= m * power) return m * power;
  }
  return 10.0 * power;
}

// A millisecond axis, linear from 0 or logarithmic over whole decades (so that passes 100x
// shorter than the longest still get a readable bar).
struct MsAxis {
  double low = 0.0, high = 1.0;
  bool logarithmic = false;

  double fraction(double ms) const {
    if (!logarithmic) return ms / high;
    const double clamped = std::clamp(ms, low, high);
    return (std::log10(clamped) - std::log10(low)) / (std::log10(high) - std::log10(low));
  }
  // Vertical grid lines with labels under the plot, between x0 and x0 + width.
  std::string ticks(double x0, double width, int top, int bottom) const {
    std::string out;
    auto tick = [&](double v) {
      out += fmt::format(
          R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#ddd"/><text x="{0:.1f}" y="{3}" text-anchor="middle" fill="#555">{4:g}</text>)"
          "\n",
          x0 + fraction(v) * width, top, bottom, bottom + 14, v);
    };
    if (logarithmic) {
      for (double v = low; v <= high * 1.0001; v *= 10.0) tick(v);
    } else {
      const double step = niceStep(high);
      for (double v = 0.0; v <= high * 1.0001; v += step) tick(v);
    }
    return out;
  }
};

// "ms …" caption followed by a colour key for the queues that appear in the run.
std::string queueLegend(const RunResult& run, int x, int y, const std::string& caption);

inline MsAxis linearAxis(double maxMs) {
  return MsAxis{0.0, maxMs > 0 ? maxMs : 1.0, false};
}

}  // namespace fgb::harness::svg
