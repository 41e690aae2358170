// Inline SVG charts for report.html: plain elements, no scripts, readable in any browser.
#include <fgb/harness/report.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace fgb::harness {
namespace {

constexpr int kChartWidth = 760;
constexpr int kLabelWidth = 190;
constexpr int kRowHeight = 22;

std::string svgOpen(int width, int height, const std::string& title) {
  return fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" role="img" aria-label="{2}" font-family="sans-serif" font-size="12">)"
                     "\n<title>{2}</title>\n",
                     width, height, escapeXml(title));
}

std::optional<double> budgetFor(const RunResult& run, const std::string& pass) {
  if (!run.budget) return std::nullopt;
  for (const auto& line : run.budget->lines) {
    if (line.pass == pass) return line.budgetMs;
  }
  return std::nullopt;
}

std::string queueColor(const std::string& queue) {
  if (queue == "compute") return "#e08a2e";
  if (queue == "transfer") return "#4a9c5d";
  return "#3f6fb5";  // graphics
}

// A tick step of 1, 2 or 5 times a power of ten giving about five ticks over [0, max].
double niceStep(double max) {
  const double raw = std::max(max, 1e-9) / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (raw <= m * power) return m * power;
  }
  return 10.0 * power;
}

std::string axisTicks(double maxMs, double x0, double width, int top, int bottom) {
  std::string out;
  const double step = niceStep(maxMs);
  for (double v = 0.0; v <= maxMs * 1.0001; v += step) {
    const double x = x0 + v / maxMs * width;
    out += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#ddd"/><text x="{0:.1f}" y="{3}" text-anchor="middle" fill="#555">{4:g}</text>)"
                       "\n",
                       x, top, bottom, bottom + 14, v);
  }
  return out;
}

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

}  // namespace

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
  double maxMs = 0.0;
  for (const auto& p : run.passes) {
    maxMs = std::max({maxMs, p.gpu.p95, budgetFor(run, p.name).value_or(0.0) * 1.1});
  }
  maxMs = maxMs > 0 ? maxMs * 1.05 : 1.0;
  const double plotWidth = kChartWidth - kLabelWidth - 20;
  std::string svg = svgOpen(kChartWidth, height, "GPU time per pass (median, p5–p95) against budget, ms");
  svg += axisTicks(maxMs, kLabelWidth, plotWidth, 10, height - 30);
  for (std::size_t i = 0; i < run.passes.size(); ++i) {
    const auto& p = run.passes[i];
    const int y = 14 + static_cast<int>(i) * kRowHeight;
    auto xOf = [&](double ms) { return kLabelWidth + ms / maxMs * plotWidth; };
    svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)" "\n", kLabelWidth - 6, y + 12,
                       escapeXml(p.name + (p.culled ? " (culled)" : "")));
    const std::optional<double> budget = budgetFor(run, p.name);
    const bool over = budget && p.gpu.median > *budget;
    svg += fmt::format(R"(<rect x="{}" y="{}" width="{:.1f}" height="14" fill="{}"><title>{}: median {:.4f} ms</title></rect>)" "\n",
                       kLabelWidth, y, xOf(p.gpu.median) - kLabelWidth, over ? "#c0392b" : queueColor(p.queue),
                       escapeXml(p.name), p.gpu.median);
    if (p.gpu.n > 1) {
      svg += fmt::format(R"(<line x1="{:.1f}" y1="{}" x2="{:.1f}" y2="{}" stroke="#222"/>)" "\n", xOf(p.gpu.p5), y + 7,
                         xOf(p.gpu.p95), y + 7);
    }
    if (budget) {
      svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#000" stroke-width="2" stroke-dasharray="3,2"><title>budget {3} ms</title></line>)" "\n",
                         xOf(*budget), y - 2, y + 16, *budget);
    }
  }
  svg += queueLegend(run, 10, height - 2,
                     run.budget ? "ms · bar: median, line: p5–p95 · dashed: budget, red: over budget"
                                : "ms · bar: median, line: p5–p95");
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
  std::string svg = svgOpen(kChartWidth, kHeight, "Frame time per measured frame, ms");
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

std::string queueTimelineSvg(const RunResult& run) {
  // Lanes in a fixed order; passes placed at their median start offset when the workload reported
  // timestamps, otherwise back to back per queue in declaration order (marked as such).
  std::vector<std::string> queues;
  for (const auto& p : run.passes) {
    if (!p.culled && std::find(queues.begin(), queues.end(), p.queue) == queues.end()) queues.push_back(p.queue);
  }
  const bool measuredStarts = std::any_of(run.passes.begin(), run.passes.end(), [](const auto& p) { return !p.startMs.empty(); });
  struct Box {
    std::string name, queue;
    double start, duration;
  };
  std::vector<Box> boxes;
  std::map<std::string, double> cursor;
  double end = 0.0;
  for (const auto& p : run.passes) {
    if (p.culled) continue;
    const double start = measuredStarts && !p.startMs.empty() ? summarize(p.startMs).median : cursor[p.queue];
    boxes.push_back({p.name, p.queue, start, p.gpu.median});
    cursor[p.queue] = start + p.gpu.median;
    end = std::max(end, start + p.gpu.median);
  }
  end = end > 0 ? end * 1.05 : 1.0;
  constexpr int kLane = 34, kLeft = 90;
  const int height = static_cast<int>(queues.size()) * kLane + 50;
  const double plotWidth = kChartWidth - kLeft - 20;
  std::string svg = svgOpen(kChartWidth, height, "Per-queue timeline of one frame (median times), ms");
  svg += axisTicks(end, kLeft, plotWidth, 6, height - 30);
  for (std::size_t q = 0; q < queues.size(); ++q) {
    svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{}</text>)" "\n", kLeft - 6, 10 + q * kLane + 18,
                       escapeXml(queues[q]));
  }
  std::map<std::string, std::vector<std::pair<double, double>>> labelled;  // x extents of outside labels, per lane
  for (const auto& b : boxes) {
    const auto lane = static_cast<std::size_t>(std::find(queues.begin(), queues.end(), b.queue) - queues.begin());
    const double x = kLeft + b.start / end * plotWidth;
    const double w = std::max(1.0, b.duration / end * plotWidth);
    svg += fmt::format(R"(<rect x="{:.1f}" y="{}" width="{:.1f}" height="26" fill="{}" stroke="#fff"><title>{}: {:.4f} ms at {:.4f} ms</title></rect>)" "\n",
                       x, 10 + lane * kLane, w, queueColor(b.queue), escapeXml(b.name), b.duration, b.start);
    if (w > 40) {
      svg += fmt::format(R"(<text x="{:.1f}" y="{}" fill="#fff" font-size="10">{}</text>)" "\n", x + 3, 10 + lane * kLane + 17,
                         escapeXml(b.name.substr(0, static_cast<std::size_t>(w / 6))));
    } else {
      // Too narrow for its name: write it in dark text after the box, or before it, on whichever
      // side has room up to the neighbouring box in the lane (and inside the chart).
      double after = kChartWidth - 4 - (x + w), before = x - kLeft;
      for (const auto& other : boxes) {
        if (other.queue != b.queue || &other == &b) continue;
        const double otherX = kLeft + other.start / end * plotWidth;
        const double otherEnd = otherX + std::max(1.0, other.duration / end * plotWidth);
        if (other.start > b.start) after = std::min(after, otherX - (x + w));
        else before = std::min(before, x - otherEnd);
      }
      constexpr double kCharWidth = 5.6;  // at font-size 10
      const auto fits = [&](double room) { return static_cast<std::size_t>(std::max(0.0, (room - 6) / kCharWidth)); };
      const bool right = fits(after) >= b.name.size() || fits(after) >= fits(before);
      const std::size_t chars = right ? fits(after) : fits(before);
      const std::string label = b.name.size() <= chars ? b.name : b.name.substr(0, chars > 0 ? chars - 1 : 0) + "…";
      const double width = kCharWidth * static_cast<double>(std::min(chars, b.name.size()));
      const double from = right ? x + w + 3 : x - 3 - width, to = from + width;
      auto& used = labelled[b.queue];  // one label may not cover another in the same lane
      const bool clear = std::none_of(used.begin(), used.end(), [&](const auto& r) { return from < r.second && r.first < to; });
      if (chars >= 4 && clear) {
        used.emplace_back(from, to);
        svg += fmt::format(R"(<text x="{:.1f}" y="{}" fill="#222" font-size="10" text-anchor="{}">{}</text>)" "\n",
                           right ? x + w + 3 : x - 3, 10 + lane * kLane + 17, right ? "start" : "end", escapeXml(label));
      }
    }
  }
  svg += fmt::format(R"(<text x="{}" y="{}" fill="#555">ms{}</text>)" "\n", kLeft, height - 2,
                     measuredStarts ? " (start times from GPU timestamps)"
                                    : " (no start timestamps reported: passes drawn back to back per queue)");
  return svg + "</svg>\n";
}

}  // namespace fgb::harness
