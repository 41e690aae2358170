// The report's queue timeline: one measured frame as the GPU ran it. Each pass is drawn from its own
// begin to its end timestamp in its queue's lane, so work on different queues that overlapped in
// time shows as overlapping boxes (and a shaded band). Below the lanes, one row per pass on the same
// time axis with its times in words, so a pass of a fraction of a percent of the frame stays
// readable. Passes the device gave no begin timestamp for are named, not guessed.
#include <fmt/format.h>

#include <algorithm>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/stats/stats.hpp>
#include <map>
#include <numeric>
#include <tuple>
#include <vector>

#include "svg_common.hpp"

namespace fgb::harness {
namespace {

using namespace svg;

struct Span {
  const PassRecord* pass;
  double begin, end;
};

// The measured frame whose GPU time is the median: a typical frame, drawn with its real times.
std::size_t medianFrame(const RunResult& run) {
  std::vector<std::size_t> order(run.frameGpuMs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return run.frameGpuMs[a] < run.frameGpuMs[b]; });
  return order.empty() ? 0 : order[order.size() / 2];
}

struct Timeline {
  std::vector<Span> spans;                // in begin order
  std::vector<std::string> queues;        // lanes, in first-declared order
  std::vector<std::string> withoutBegin;  // passes with GPU time, but without a begin timestamp
  std::vector<std::string> noWork;        // passes that recorded no GPU work (no timestamps at all)
  bool measured = false;                  // false: no begin at all, drawn back to back
  std::size_t frame = 0;
  double end = 0.0;
};

Timeline layOut(const RunResult& run) {
  Timeline t;
  t.frame = medianFrame(run);
  for (const auto& p : run.passes) {
    if (p.culled) continue;
    if (std::find(t.queues.begin(), t.queues.end(), p.queue) == t.queues.end()) t.queues.push_back(p.queue);
    if (!p.startMs.empty()) t.measured = true;
  }
  std::map<std::string, double> cursor;  // back-to-back placement when the device gives no begin
  for (const auto& p : run.passes) {
    if (p.culled) continue;
    if (t.measured && p.startMs.empty()) {
      const bool anyTime = std::any_of(p.samplesMs.begin(), p.samplesMs.end(), [](double ms) { return ms > 0.0; });
      (anyTime ? t.withoutBegin : t.noWork).push_back(p.name);
      continue;
    }
    const double duration = t.frame < p.samplesMs.size() ? p.samplesMs[t.frame] : p.gpu.median;
    const double begin = t.measured ? p.startMs[std::min(t.frame, p.startMs.size() - 1)] : cursor[p.queue];
    cursor[p.queue] = begin + duration;
    t.spans.push_back({&p, begin, begin + duration});
    t.end = std::max(t.end, begin + duration);
  }
  std::stable_sort(t.spans.begin(), t.spans.end(), [](const Span& a, const Span& b) { return a.begin < b.begin; });
  return t;
}

// Intervals during which passes of at least two queues were running (a sweep over begin/end events).
std::vector<std::pair<double, double>> overlaps(const Timeline& t) {
  std::vector<std::tuple<double, int, std::string>> events;  // time, +1 begin / -1 end (ends first), queue
  for (const Span& s : t.spans) {
    events.emplace_back(s.begin, +1, s.pass->queue);
    events.emplace_back(s.end, -1, s.pass->queue);
  }
  std::sort(events.begin(), events.end(), [](const auto& a, const auto& b) {
    return std::get<0>(a) != std::get<0>(b) ? std::get<0>(a) < std::get<0>(b) : std::get<1>(a) < std::get<1>(b);
  });
  std::map<std::string, int> running;
  int busyQueues = 0;
  double since = 0.0;
  std::vector<std::pair<double, double>> out;
  for (const auto& [time, step, queue] : events) {
    const bool wasOverlapping = busyQueues >= 2;
    int& count = running[queue];
    if (step > 0 && count++ == 0) ++busyQueues;
    if (step < 0 && --count == 0) --busyQueues;
    if (!wasOverlapping && busyQueues >= 2) since = time;
    if (wasOverlapping && busyQueues < 2 && time > since) out.emplace_back(since, time);
  }
  return out;
}

std::string caption(const Timeline& t, double overlapMs) {
  if (!t.measured)
    return "ms · this device reports no begin timestamps: passes drawn back to back per queue, not at their real times";
  std::string text =
      fmt::format("ms · measured frame {} (median GPU time) from GPU begin/end timestamps · queues overlap {:.4f} ms",
                  t.frame + 1, overlapMs);
  return text;
}

// Where things go: lanes on top, one row per pass under them, three lines of text at the bottom.
struct Geometry {
  static constexpr int kLane = 34, kRow = 16, kTop = 6;
  MsAxis axis;
  double plotWidth = kChartWidth - kLabelWidth - 20;
  int lanesBottom = 0, rowsTop = 0, height = 0;

  explicit Geometry(const Timeline& t)
      : axis(linearAxis(t.end > 0 ? t.end * 1.05 : 1.0)),
        lanesBottom(kTop + static_cast<int>(t.queues.size()) * kLane),
        rowsTop(lanesBottom + 26),
        height(rowsTop + static_cast<int>(t.spans.size()) * kRow + 44 + (t.withoutBegin.empty() ? 0 : 16) +
               (t.noWork.empty() ? 0 : 16)) {}
  double x(double ms) const { return kLabelWidth + axis.fraction(ms) * plotWidth; }
};

// Shaded bands where queues overlap; returns the overlapping time.
double drawOverlaps(std::string& svg, const Timeline& t, const Geometry& g) {
  double overlapMs = 0.0;
  for (const auto& [from, to] : overlaps(t)) {
    overlapMs += to - from;
    svg += fmt::format(
        R"(<rect class="overlap" x="{:.1f}" y="{}" width="{:.1f}" height="{}" fill="#6a4c93" opacity="0.15"><title>queues overlap for {:.4f} ms</title></rect>)"
        "\n",
        g.x(from), Geometry::kTop, std::max(1.0, g.x(to) - g.x(from)), g.lanesBottom - Geometry::kTop, to - from);
  }
  return overlapMs;
}

void drawLanes(std::string& svg, const Timeline& t, const Geometry& g) {
  for (std::size_t q = 0; q < t.queues.size(); ++q) {
    svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end">{} queue</text>)"
                       "\n",
                       kLabelWidth - 6, Geometry::kTop + static_cast<int>(q) * Geometry::kLane + 18,
                       escapeXml(t.queues[q]));
  }
  for (const Span& s : t.spans) {
    const auto lane = std::find(t.queues.begin(), t.queues.end(), s.pass->queue) - t.queues.begin();
    const double x = g.x(s.begin), w = std::max(1.5, g.x(s.end) - x);
    const int y = Geometry::kTop + static_cast<int>(lane) * Geometry::kLane;
    svg += fmt::format(
        R"(<rect class="span" data-pass="{}" x="{:.1f}" y="{}" width="{:.1f}" height="26" fill="{}" stroke="#fff" stroke-width="0.5"><title>{}: {:.4f} → {:.4f} ms</title></rect>)"
        "\n",
        escapeXml(s.pass->name), x, y, w, queueColor(s.pass->queue), escapeXml(s.pass->name), s.begin, s.end);
    if (w > 40) {
      svg += fmt::format(R"(<text x="{:.1f}" y="{}" fill="#fff" font-size="10">{}</text>)"
                         "\n",
                         x + 3, y + 17, escapeXml(s.pass->name.substr(0, static_cast<std::size_t>(w / 6))));
    }
  }
}

// One row per pass, in begin order: readable however short the pass is.
void drawRows(std::string& svg, const Timeline& t, const Geometry& g) {
  for (std::size_t i = 0; i < t.spans.size(); ++i) {
    const Span& s = t.spans[i];
    const int y = g.rowsTop + static_cast<int>(i) * Geometry::kRow;
    const double x = g.x(s.begin), w = std::max(2.0, g.x(s.end) - x);
    const double share = t.end > 0 ? 100.0 * (s.end - s.begin) / t.end : 0.0;
    svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="end" font-size="11">{}</text>)"
                       "\n",
                       kLabelWidth - 6, y + 10, escapeXml(s.pass->name));
    svg += fmt::format(R"(<rect class="row-bar" x="{:.1f}" y="{}" width="{:.1f}" height="10" fill="{}"/>)"
                       "\n",
                       x, y + 1, w, queueColor(s.pass->queue));
    // Times after the bar; inside it (white) when the bar reaches the right edge; else before it.
    const std::string times = fmt::format("{:.4f} ms ({:.2g}%) at {:.4f}", s.end - s.begin, share, s.begin);
    const double textWidth = 5.6 * static_cast<double>(times.size());
    if (x + w + 4 + textWidth < kChartWidth) {
      svg += fmt::format(R"(<text x="{:.1f}" y="{}" font-size="10" fill="#444">{}</text>)"
                         "\n",
                         x + w + 4, y + 10, times);
    } else if (w > textWidth + 8) {
      svg += fmt::format(R"(<text x="{:.1f}" y="{}" font-size="10" fill="#fff">{}</text>)"
                         "\n",
                         x + 4, y + 10, times);
    } else {
      svg += fmt::format(R"(<text x="{:.1f}" y="{}" font-size="10" fill="#444" text-anchor="end">{}</text>)"
                         "\n",
                         x - 4, y + 10, times);
    }
  }
}

// Bottom lines, from the bottom up: queue colours, what the chart shows, passes left out.
void drawFooter(std::string& svg, const RunResult& run, const Timeline& t, const Geometry& g, double overlapMs) {
  svg += queueLegend(run, 10, g.height - 2, "queues:");
  svg += fmt::format(R"(<text x="10" y="{}" fill="#555">{}</text>)"
                     "\n",
                     g.height - 18, escapeXml(caption(t, overlapMs)));
  int y = g.height - 34;
  auto note = [&](const std::vector<std::string>& passes, const char* colour, const char* what) {
    if (passes.empty()) return;
    std::string names;
    for (const auto& n : passes) names += (names.empty() ? "" : ", ") + n;
    svg += fmt::format(R"(<text x="10" y="{}" fill="{}">{}: {}</text>)"
                       "\n",
                       y, colour, what, escapeXml(names));
    y -= 16;
  };
  note(t.withoutBegin, "#c0392b", "not drawn, the device gave no begin timestamp for");
  note(t.noWork, "#555", "not drawn, recorded no GPU work");
}

}  // namespace

std::string queueTimelineSvg(const RunResult& run) {
  const Timeline t = layOut(run);
  const Geometry g(t);
  std::string svg = open(kChartWidth, g.height, "chart-timeline", "Per-queue timeline of one frame, ms");
  svg += g.axis.ticks(kLabelWidth, g.plotWidth, Geometry::kTop, g.lanesBottom + 4);
  const double overlapMs = drawOverlaps(svg, t, g);
  drawLanes(svg, t, g);
  drawRows(svg, t, g);
  drawFooter(svg, run, t, g, overlapMs);
  return svg + "</svg>\n";
}

}  // namespace fgb::harness
