// Inline SVG charts for report.html: pass bars against budget and the frame time series (the
// queue timeline is in svg_timeline.cpp). Plain elements, readable in any browser.
#include <fgb/harness/report/report.hpp>

#include "svg_common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace fgb::harness {
namespace {

using namespace svg;

std::optional<double> budgetFor(const RunResult& run, const std::string& pass) {
  if (!run.budget) return std::nullopt;
  for (const auto& line : run.budget->lines) {
    if (line.pass == pass) return line.budgetMs;
  }
  return std::nullopt;
}

// Linear from 0, or logarithmic when the shortest pass's median is under 1/30 of the longest's:
// on a linear axis such a pass would be a bar of a pixel or two.
MsAxis passAxis(const RunResult& run) {
  double maxMs = 0.0, longestPass = 0.0, shortestPass = 0.0;
  for (const auto& p : run.passes) {
    if (p.culled) continue;
    maxMs = std::max({maxMs, p.gpu.p95, budgetFor(run, p.name).value_or(0.0) * 1.1});
    longestPass = std::max(longestPass, p.gpu.median);
    if (p.gpu.median > 0 && (shortestPass == 0.0 || p.gpu.median < shortestPass)) shortestPass = p.gpu.median;
  }
  if (shortestPass > 0 && longestPass / shortestPass > 30.0) {
    return MsAxis{std::pow(10.0, std::floor(std::log10(shortestPass))), std::pow(10.0, std::ceil(std::log10(maxMs * 1.05))), true};
  }
  return linearAxis(maxMs * 1.05);
}

}  // namespace

namespace svg {

// "ms …" caption followed by a colour key for the queues that appear in the run.
std::string queueLegend(const RunResult& run, int x, int y, const std::string& caption) {
  std::vector<std::string> queues;
  for (const auto& p : run.passes) {
    if (std::find(queues.begin(), queues.end(), p.queue) == queues.end()) queues.push_back(p.queue);
  }
  std::string out = fmt::format(R"(<text x="{}" y="{}" fill="#555">{}</text>)" "\n", x, y, escapeXml(caption));
  double at = x + 6.2 * static_cast<double>(caption.size()) + 16;  // about 6 px per character at 12 px
  for (const auto& q : queues) {
    out += fmt::format(R"(<rect x="{0:.1f}" y="{1}" width="10" height="10" fill="{2}"/><text x="{3:.1f}" y="{4}" fill="#555">{5}</text>)" "\n",
                       at, y - 9, queueColor(q), at + 13, y, escapeXml(q));
    at += 13 + 7.0 * static_cast<double>(q.size()) + 12;
  }
  return out;
}

}  // namespace svg

std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string passBarsSvg(const RunResult& run) {
  const int height = static_cast<int>(run.passes.size()) * kRowHeight + 50;
  const MsAxis axis = passAxis(run);
  const double plotWidth = kChartWidth - kLabelWidth - 20;
  auto xOf = [&](double ms) { return kLabelWidth + axis.fraction(ms) * plotWidth; };
  std::string svg = open(kChartWidth, height, "chart-passes", "GPU time per pass (median, p5–p95) against budget, ms");
  svg += axis.ticks(kLabelWidth, plotWidth, 10, height - 30);
  for (std::size_t i = 0; i < run.passes.size(); ++i) {
    const auto& p = run.passes[i];
    const int y = 14 + static_cast<int>(i) * kRowHeight;
    svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)" "\n", kLabelWidth - 6, y + 12,
                       escapeXml(p.name + (p.culled ? " (culled)" : "")));
    if (p.culled) continue;
    const std::optional<double> budget = budgetFor(run, p.name);
    // The bar is the cost budgets judge: isolated where the run was calibrated, the span else; a
    // span longer than the isolated cost shows as a faint extension (time the pass waited or shared).
    const double judged = p.hasIsolated() ? p.isolated.median : p.gpu.median;
    const bool over = budget && judged > *budget;
    if (p.hasIsolated() && p.gpu.median > judged) {
      svg += fmt::format(
          R"(<rect class="span-extension" x="{:.1f}" y="{}" width="{:.1f}" height="14" fill="{}" opacity="0.3"><title>{}: span {:.4f} ms</title></rect>)"
          "\n",
          xOf(judged), y, std::max(0.5, xOf(p.gpu.median) - xOf(judged)), queueColor(p.queue), escapeXml(p.name),
          p.gpu.median);
    }
    svg += fmt::format(
        R"(<rect class="bar" x="{}" y="{}" width="{:.1f}" height="14" fill="{}"><title>{}: {} {:.4f} ms{}</title></rect>)"
        "\n",
        kLabelWidth, y, std::max(1.0, xOf(judged) - kLabelWidth), over ? "#c0392b" : queueColor(p.queue),
        escapeXml(p.name), p.hasIsolated() ? "isolated median" : "median", judged,
        p.hasIsolated() ? fmt::format(", span {:.4f} ms", p.gpu.median) : "");
    if (p.gpu.n > 1) {
      svg += fmt::format(R"(<line x1="{:.1f}" y1="{}" x2="{:.1f}" y2="{}" stroke="#222"/>)" "\n", xOf(p.gpu.p5), y + 7,
                         xOf(p.gpu.p95), y + 7);
    }
    if (budget) {
      svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#000" stroke-width="2" stroke-dasharray="3,2"><title>budget {3} ms</title></line>)" "\n",
                         xOf(*budget), y - 2, y + 16, *budget);
    }
  }
  const std::string scale = axis.logarithmic ? "ms, log scale" : "ms";
  svg +=
      queueLegend(run, 10, height - 2,
                  (run.isolatedFrames > 0 ? scale + " · bar: isolated cost (pass alone), faint: span, line: span p5–p95"
                                          : scale + " · bar: median, line: p5–p95") +
                      (run.budget ? " · dashed: budget, red: over budget" : ""));
  return svg + "</svg>\n";
}

std::string frameSeriesSvg(const RunResult& run) {
  constexpr int kHeight = 236, kLeft = 50, kTop = 22, kBottom = 198;
  const std::size_t n = std::max(run.frameGpuMs.size(), run.frameCpuMs.size());
  double maxMs = 0.0;
  for (double v : run.frameGpuMs) maxMs = std::max(maxMs, v);
  for (double v : run.frameCpuMs) maxMs = std::max(maxMs, v);
  maxMs = maxMs > 0 ? maxMs * 1.1 : 1.0;
  const double plotWidth = kChartWidth - kLeft - 20;
  std::string svg = open(kChartWidth, kHeight, "chart-frames", "Frame time per measured frame, ms");
  const double step = niceStep(maxMs);
  for (double v = 0.0; v <= maxMs; v += step) {
    const double y = kBottom - v / maxMs * (kBottom - kTop);
    svg += fmt::format(R"(<line x1="{0}" y1="{1:.1f}" x2="{2}" y2="{1:.1f}" stroke="#ddd"/><text x="{3}" y="{4:.1f}" text-anchor="end" fill="#555">{5:g}</text>)" "\n",
                       kLeft, y, kChartWidth - 20, kLeft - 4, y + 4, v);
  }
  auto xOfFrame = [&](std::size_t i) {
    return kLeft + (n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.5) * plotWidth;
  };
  if (n > 0) {  // frame numbers (1-based) under the plot
    const auto frameStep = static_cast<std::size_t>(std::max(1.0, niceStep(static_cast<double>(n))));
    for (std::size_t frame = 1; frame <= n; frame = frame == 1 && frameStep > 1 ? frameStep : frame + frameStep) {
      svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#999"/><text x="{0:.1f}" y="{3}" text-anchor="middle" fill="#555">{4}</text>)" "\n",
                         xOfFrame(frame - 1), kBottom, kBottom + 4, kBottom + 15, frame);
    }
  }
  svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end" fill="#555">ms</text>)" "\n", kLeft - 4, kTop - 10);
  auto polyline = [&](const std::vector<double>& series, const char* color, const char* name) {
    if (series.empty()) return std::string();
    std::string points;
    for (std::size_t i = 0; i < series.size(); ++i) {
      const double x = xOfFrame(i);
      const double y = kBottom - series[i] / maxMs * (kBottom - kTop);
      points += fmt::format("{:.1f},{:.1f} ", x, y);
    }
    return fmt::format(R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5"><title>{}</title></polyline>)" "\n",
                       points, color, name);
  };
  svg += polyline(run.frameGpuMs, "#3f6fb5", "GPU frame time");
  svg += polyline(run.frameCpuMs, "#e08a2e", "CPU frame time");
  svg += fmt::format(R"(<text x="{}" y="{}" fill="#3f6fb5">— GPU frame</text><text x="{}" y="{}" fill="#e08a2e">— CPU frame (recording)</text><text x="{}" y="{}" fill="#555">measured frame 1 … {}</text>)" "\n",
                     kLeft, kHeight - 2, kLeft + 90, kHeight - 2, kLeft + 330, kHeight - 2, n);
  return svg + "</svg>\n";
}

}  // namespace fgb::harness
