// sweep.html: one self-contained file (inline SVG charts, images as data: URIs, no scripts).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fgb/harness/image_io.hpp>
#include <fgb/harness/report.hpp>
#include <fgb/harness/sweep_report.hpp>

namespace fgb::harness {
namespace {

constexpr uint32_t kThumbnailWidth = 420;  // gallery images are shrunk to this width at most

constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
    "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
    "td:first-child,th:first-child,td:nth-child(2){text-align:left}.front{background:#fff3e0;font-weight:bold}"
    ".note{color:#555}.pick{font-size:1.1em;background:#fff3e0;padding:.6em 1em;border-left:4px solid #e8710a}"
    ".gallery{display:flex;flex-wrap:wrap;gap:18px}.gallery figure{margin:0}.gallery img{display:block;"
    "image-rendering:pixelated;border:1px solid #ccc}.pair{display:flex;gap:4px}figcaption{font-size:.9em}";

constexpr std::array<const char*, 12> kPassColors = {"#3f6fb5", "#e08a2e", "#4a9c5d", "#c0392b", "#8e6bbf", "#8c564b",
                                                     "#d45fb0", "#7f7f7f", "#bcbd22", "#17becf", "#1f3f6f", "#f2b134"};

std::string imgTag(const Image& image, const std::string& alt) {
  const Image thumb = shrinkToWidth(image, kThumbnailWidth);
  return fmt::format(R"(<img src="{}" width="{}" height="{}" alt="{}">)", pngDataUri(encodePng(thumb)), thumb.width,
                     thumb.height, escapeXml(alt));
}

// A log10 axis over [lo, hi]: position of a value and tick values (1, 2, 5 x 10^k inside the range,
// or the ends when the range holds fewer than two of those).
struct LogAxis {
  double lo, hi;
  double at(double v, double from, double to) const {
    const double t = (std::log10(std::max(v, lo)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    return from + t * (to - from);
  }
  std::vector<double> ticks() const {
    std::vector<double> out;
    for (int e = static_cast<int>(std::floor(std::log10(lo))); e <= static_cast<int>(std::ceil(std::log10(hi))); ++e) {
      for (double m : {1.0, 2.0, 5.0}) {
        const double v = m * std::pow(10.0, e);
        if (v >= lo && v <= hi) out.push_back(v);
      }
    }
    if (out.size() < 2) out = {lo, std::sqrt(lo * hi), hi};
    return out;
  }
};

LogAxis paddedLogAxis(double lo, double hi) {
  if (!(lo > 0)) lo = 1e-6;
  if (!(hi > lo)) hi = lo * 1.0001;
  // At least a factor 1.5 across, centred on the data, so close points do not fill the whole plot.
  const double centre = std::sqrt(lo * hi);
  const double half = std::max(std::sqrt(hi / lo), std::sqrt(1.5)) * 1.08;
  return {centre / half, centre * half};
}

std::string tickLabel(double v) {
  return fmt::format("{:.3g}", v);
}

}  // namespace

std::string timeErrorSvg(const SweepResult& result) {
  constexpr int W = 860, H = 480, left = 80, right = 220, top = 30, bottom = 60;
  const double plotRight = W - right, plotBottom = H - bottom;
  double tLo = 1e300, tHi = 0, eLo = 1e300, eHi = 0;
  for (const auto& c : result.configurations) {
    tLo = std::min(tLo, c.frameGpu.lower);
    tHi = std::max(tHi, c.frameGpu.upper);
    const double e = sweepError(c);
    if (e > 0) eLo = std::min(eLo, std::max(e - result.errorFloor, e / 2));
    eHi = std::max(eHi, e + result.errorFloor);
  }
  if (eHi <= 0) eHi = 1e-3;
  if (eLo > eHi) eLo = eHi / 10;
  const LogAxis x = paddedLogAxis(tLo, tHi), y = paddedLogAxis(eLo, eHi);
  auto px = [&](double v) { return x.at(v, left, plotRight); };
  auto py = [&](double v) { return y.at(v, plotBottom, top); };

  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12" role="img" aria-label="GPU frame time against error">)"
      "\n<title>GPU frame time against error (log-log), Pareto front</title>\n",
      W, H);
  for (double v : x.ticks()) {
    svg += fmt::format(
        R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#e4e4e4"/><text x="{0:.1f}" y="{3}" text-anchor="middle" fill="#555">{4}</text>)"
        "\n",
        px(v), top, plotBottom, plotBottom + 16, tickLabel(v));
  }
  for (double v : y.ticks()) {
    svg += fmt::format(
        R"(<line x1="{1}" y1="{0:.1f}" x2="{2}" y2="{0:.1f}" stroke="#e4e4e4"/><text x="{3}" y="{4:.1f}" text-anchor="end" fill="#555">{5}</text>)"
        "\n",
        py(v), left, plotRight, left - 6, py(v) + 4, tickLabel(v));
  }
  svg += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#999"/>)"
                     "\n",
                     left, top, plotRight - left, plotBottom - top);
  svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">GPU frame time, ms (median, 95% CI; log)</text>)"
                     "\n",
                     (left + plotRight) / 2, H - 18);
  svg += fmt::format(
      R"svg(<text transform="translate(18 {}) rotate(-90)" text-anchor="middle">LDR-FLIP vs reference (± noise floor; log)</text>)svg"
      "\n",
      (top + plotBottom) / 2);

  // The front as a line, fastest to slowest.
  std::string line;
  for (std::size_t i : frontByTime(result)) {
    const auto& c = result.configurations[i];
    line += fmt::format("{:.1f},{:.1f} ", px(c.frameGpu.median), py(sweepError(c)));
  }
  svg += fmt::format(R"(<polyline points="{}" fill="none" stroke="#e8710a" stroke-width="2" stroke-dasharray="6 3"/>)"
                     "\n",
                     line);

  for (const auto& c : result.configurations) {
    const double e = sweepError(c), cx = px(c.frameGpu.median), cy = py(e);
    const char* colour = c.onFront ? "#e8710a" : "#888";
    svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}"/>)"
                       "\n",
                       px(c.frameGpu.lower), cy, px(c.frameGpu.upper), cy, colour);
    if (result.errorFloor > 0) {
      svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}"/>)"
                         "\n",
                         cx, py(std::max(e - result.errorFloor, y.lo)), cx, py(e + result.errorFloor), colour);
    }
    svg += fmt::format(
        R"(<circle cx="{:.1f}" cy="{:.1f}" r="5" fill="{}" stroke="{}" stroke-width="1.5"><title>{}: {:.4f} ms [{:.4f}, {:.4f}], LDR-FLIP {:.5f}{}</title></circle>)"
        "\n",
        cx, cy, c.onFront ? colour : "white", colour, escapeXml(c.configuration.label), c.frameGpu.median,
        c.frameGpu.lower, c.frameGpu.upper, e, c.onFront ? " (front)" : "");
    // An error of 0 (the reference's own image) has no place on a log axis: it sits on the bottom
    // edge and says so.
    svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" fill="{}"{}>{}{}</text>)"
                       "\n",
                       cx + 8, cy - 7, c.onFront ? "#b35300" : "#777", c.onFront ? R"( font-weight="bold")" : "",
                       escapeXml(c.configuration.label), e > 0 ? "" : " (error 0: as the reference)");
  }
  svg += fmt::format(
      R"(<circle cx="{0}" cy="{1}" r="5" fill="#e8710a"/><text x="{2}" y="{3}">on the Pareto front</text>)"
      R"(<circle cx="{0}" cy="{4}" r="5" fill="white" stroke="#888" stroke-width="1.5"/><text x="{2}" y="{5}">dominated</text>)"
      "\n",
      plotRight + 20, top + 10, plotRight + 32, top + 14, top + 30, top + 34);
  return svg + "</svg>\n";
}

std::string passStackSvg(const SweepResult& result) {
  constexpr int W = 860, label = 260, row = 24, legendRow = 18;
  std::vector<std::string> passes;  // every measured pass, first-seen order: one colour each
  double maxTotal = 0;
  for (const auto& c : result.configurations) {
    double total = 0;
    for (const auto& p : c.run.passes) {
      if (p.culled) continue;
      if (std::find(passes.begin(), passes.end(), p.name) == passes.end()) passes.push_back(p.name);
      total += p.gpu.median;
    }
    maxTotal = std::max(maxTotal, total);
  }
  if (maxTotal <= 0) maxTotal = 1;
  const int legendRows = static_cast<int>((passes.size() + 3) / 4);
  const int H = static_cast<int>(result.configurations.size()) * row + 40 + legendRows * legendRow;
  const double plotWidth = W - label - 70;
  auto colourOf = [&](const std::string& name) {
    const auto index = static_cast<std::size_t>(std::find(passes.begin(), passes.end(), name) - passes.begin());
    return kPassColors[index % kPassColors.size()];
  };
  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12" role="img" aria-label="Per-pass GPU time per configuration">)"
      "\n<title>Per-pass median GPU time per configuration, ms</title>\n",
      W, H);
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    const auto& c = result.configurations[i];
    const int yTop = 8 + static_cast<int>(i) * row;
    svg +=
        fmt::format(R"(<text x="{}" y="{}" text-anchor="end"{}>{}</text>)"
                    "\n",
                    label - 6, yTop + 13, c.onFront ? R"( font-weight="bold")" : "", escapeXml(c.configuration.label));
    double at = label, total = 0;
    for (const auto& p : c.run.passes) {
      if (p.culled) continue;
      const double w = p.gpu.median / maxTotal * plotWidth;
      svg += fmt::format(
          R"(<rect x="{:.1f}" y="{}" width="{:.2f}" height="16" fill="{}"><title>{}: {}: {:.4f} ms</title></rect>)"
          "\n",
          at, yTop, w, colourOf(p.name), escapeXml(c.configuration.label), escapeXml(p.name), p.gpu.median);
      at += w;
      total += p.gpu.median;
    }
    svg += fmt::format(R"(<text x="{:.1f}" y="{}" fill="#555">{:.3f} ms</text>)"
                       "\n",
                       at + 4, yTop + 13, total);
  }
  const int legendTop = static_cast<int>(result.configurations.size()) * row + 22;
  for (std::size_t k = 0; k < passes.size(); ++k) {
    const double lx = 10 + static_cast<double>(k % 4) * 210;
    const int ly = legendTop + static_cast<int>(k / 4) * legendRow;
    svg += fmt::format(R"(<rect x="{:.0f}" y="{}" width="10" height="10" fill="{}"/><text x="{:.0f}" y="{}">{}</text>)"
                       "\n",
                       lx, ly - 9, colourOf(passes[k]), lx + 14, ly, escapeXml(passes[k]));
  }
  return svg + "</svg>\n";
}

std::string sweepHtml(const SweepResult& result) {
  std::string html = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>fgbench sweep: "
      "{0}</title><style>{1}</style></head><body>\n"
      "<h1>Sweep: {0}</h1>\n<p>{2} ({3}), {4} configuration(s), {5} reference(s).</p>\n",
      escapeXml(result.scene), kStyle, escapeXml(result.device.name), escapeXml(result.device.driver),
      result.configurations.size(), result.references.size());
  if (result.device.hostTimestamps)
    html += "<p class=\"note\">" + escapeXml(timestampSourceNote(result.device)) + "</p>\n";

  html += "<p class=\"pick\"><b>Pareto front, fastest first:</b> ";
  bool first = true;
  for (std::size_t i : frontByTime(result)) {
    const auto& c = result.configurations[i];
    html += fmt::format("{}<b>{}</b> ({:.3f} ms, LDR-FLIP {:.4f})", first ? "" : " &rarr; ",
                        escapeXml(c.configuration.label), c.frameGpu.median, sweepError(c));
    first = false;
  }
  html +=
      ".<br>Pick the fastest point on the front whose error you can accept; every other configuration is slower "
      "without being more accurate, or less accurate without being faster.</p>\n";

  html += "<h2>Time against error</h2>\n" + timeErrorSvg(result);
  html +=
      "<h2>Configurations</h2>\n<table><tr><th>configuration</th><th>front</th><th>GPU frame ms</th><th>95% CI</th>"
      "<th>frames</th><th>LDR-FLIP</th><th>HDR-FLIP</th><th>RMSE</th><th>PSNR dB</th><th>NaN/Inf</th><th>dominated "
      "by</th></tr>\n";
  for (const auto& c : result.configurations) {
    std::string dominatedBy;
    for (std::size_t d : c.dominatedBy)
      dominatedBy += (dominatedBy.empty() ? "" : ", ") + result.configurations[d].configuration.label;
    html += fmt::format(
        "<tr{}><td>{}</td><td>{}</td><td>{:.4f}</td><td>[{:.4f}, "
        "{:.4f}]</td><td>{}</td><td>{}</td><td>{}</td><td>{:.5f}</td>"
        "<td>{}</td><td>{}</td><td>{}</td></tr>\n",
        c.onFront ? " class=\"front\"" : "", escapeXml(c.configuration.label), c.onFront ? "front" : "",
        c.frameGpu.median, c.frameGpu.lower, c.frameGpu.upper, c.frameGpu.n,
        c.display.flip ? fmt::format("{:.5f}", c.display.flip->mean) : "-",
        c.hdr.flip ? fmt::format("{:.5f}", c.hdr.flip->mean) : "-", c.display.rmse,
        std::isfinite(c.display.psnr) ? fmt::format("{:.2f}", c.display.psnr) : "&infin;",
        c.display.nonFiniteTest + c.hdr.nonFiniteTest, escapeXml(dominatedBy));
  }
  html += "</table>\n<h2>Per-pass GPU time</h2>\n" + passStackSvg(result);

  html += "<h2>Frames and LDR-FLIP against the reference</h2>\n<div class=\"gallery\">\n";
  for (std::size_t r = 0; r < result.references.size(); ++r) {
    const auto& ref = result.references[r];
    html += fmt::format("<figure>{}<figcaption>reference {} ({}; two renders {})</figcaption></figure>\n",
                        imgTag(ref.images.display, "reference"), r + 1, describeSize(ref.images.display),
                        ref.identical ? "bit-identical" : "differ");
  }
  for (const auto& c : result.configurations) {
    html += fmt::format(
        "<figure><div class=\"pair\">{}{}</div><figcaption>{}{}: {:.3f} ms, LDR-FLIP {:.4f}</figcaption></figure>\n",
        imgTag(c.images.display, c.configuration.label), imgTag(c.heatMap, "FLIP " + c.configuration.label),
        c.onFront ? "<b>front</b> " : "", escapeXml(c.configuration.label), c.frameGpu.median, sweepError(c));
  }
  html += "</div>\n<h2>Method</h2>\n<p>" + escapeXml(sweepMethodNote(result)) + "</p>\n</body></html>\n";
  return html;
}

}  // namespace fgb::harness
