// sweep.html: one self-contained file (inline SVG charts, images as data: URIs, no scripts).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/report/html_util.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>

#include "label_placement.hpp"

namespace fgb::harness {
namespace {

// 1080 px of content: a 1280 px window shows the whole page; the configurations' table scrolls
// sideways in its own box (first column and header kept in view) instead of widening the page.
constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:1080px;margin:2em auto;padding:0 1em;color:#222}"
    ".table-scroll{overflow-x:auto;max-width:100%;margin:1em 0;border:1px solid #ddd}"
    "table{border-collapse:separate;border-spacing:0}td,th{border-right:1px solid #ddd;border-bottom:1px solid #ddd;"
    "padding:3px 8px;text-align:right;white-space:nowrap;background:#fff}"
    "th{background:#f2f2f2;position:sticky;top:0;vertical-align:bottom}"
    "td:first-child,th:first-child{position:sticky;left:0;z-index:1;text-align:left}th:first-child{z-index:2}"
    "td:nth-child(2),td.dominated{text-align:left}"
    ".front td{background:#fff3e0;font-weight:bold}"
    ".unresolved{color:#3f6fb5;font-weight:normal;font-size:.85em}"
    ".note{color:#555}.pick{font-size:1.1em;background:#fff3e0;padding:.6em 1em;border-left:4px solid #e8710a}"
    ".gallery{display:flex;flex-wrap:wrap;gap:18px}.gallery figure{margin:0}.gallery img{display:block;"
    "image-rendering:pixelated;border:1px solid #ccc}.pair{display:flex;gap:4px}figcaption{font-size:.9em}"
    "svg{max-width:100%;height:auto}";

constexpr std::array<const char*, 12> kPassColors = {"#3f6fb5", "#e08a2e", "#4a9c5d", "#c0392b", "#8e6bbf", "#8c564b",
                                                     "#d45fb0", "#7f7f7f", "#bcbd22", "#17becf", "#1f3f6f", "#f2b134"};

}  // namespace

std::string timeErrorSvg(const SweepResult& result) {
  constexpr int W = 1040, right = 190, left = 80, top = 30, plotHeight = 420;
  const double plotRight = W - right, plotBottom = top + plotHeight;
  double tLo = 1e300, tHi = 0, eLo = 1e300, eHi = 0;
  for (const auto& c : result.configurations) {
    tLo = std::min(tLo, c.frameGpu.lower);
    tHi = std::max(tHi, c.frameGpu.upper);
    const double e = sweepError(c);
    if (e > 0) eLo = std::min(eLo, std::max(e - result.errorFloor, e / 2));
    eHi = std::max(eHi, e + result.errorFloor);
  }
  // The unresolved band (errors within kUnresolvedGapFactor x the reference's convergence gap) is
  // kept in view: a point inside it cannot be ranked by error.
  const double band = kUnresolvedGapFactor * largestConvergenceGap(result);
  if (band > 0) {
    eHi = std::max(eHi, band * 1.5);
    eLo = std::min(eLo, band / 2);
  }
  if (eHi <= 0) eHi = 1e-3;
  if (eLo > eHi) eLo = eHi / 10;
  const LogAxis x = paddedLogAxis(tLo, tHi), y = paddedLogAxis(eLo, eHi);
  auto px = [&](double v) { return x.at(v, left, plotRight); };
  auto py = [&](double v) { return y.at(v, plotBottom, top); };

  // Labels first: those that only fit as their number are listed under the plot.
  std::vector<LabelRequest> requests;
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    const auto& c = result.configurations[i];
    requests.push_back(
        {px(c.frameGpu.median), py(sweepError(c)), c.configuration.label, std::to_string(i + 1), c.onFront, c.onFront});
  }
  const std::vector<PlacedLabel> labels = placeLabels(requests, {left + 2.0, top + 2.0, plotRight - 2, plotBottom - 2});
  std::vector<std::size_t> numbered;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i].numbered) numbered.push_back(i);
  }
  constexpr int keyRow = 17, keyColumns = 2;
  const int keyRows = static_cast<int>((numbered.size() + keyColumns - 1) / keyColumns);
  const int H = static_cast<int>(plotBottom) + 56 + (keyRows ? 10 + keyRows * keyRow : 0);

  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" id="time-error" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12" role="img" aria-label="GPU frame time against error">)"
      "\n<title>GPU frame time against error (log-log), Pareto front</title>\n",
      W, H);
  for (double v : x.minorTicks()) {
    svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#f3f3f3"/>)"
                       "\n",
                       px(v), top, plotBottom);
  }
  for (double v : y.minorTicks()) {
    svg += fmt::format(R"(<line x1="{1}" y1="{0:.1f}" x2="{2}" y2="{0:.1f}" stroke="#f3f3f3"/>)"
                       "\n",
                       py(v), left, plotRight);
  }
  for (double v : x.ticks()) {
    svg += fmt::format(
        R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="#e4e4e4"/><text class="tick x-tick" x="{0:.1f}" y="{3}" text-anchor="middle" fill="#555">{4}</text>)"
        "\n",
        px(v), top, plotBottom, plotBottom + 16, escapeXml(durationLabel(v)));
  }
  for (double v : y.ticks()) {
    svg += fmt::format(
        R"(<line x1="{1}" y1="{0:.1f}" x2="{2}" y2="{0:.1f}" stroke="#e4e4e4"/><text class="tick y-tick" x="{3}" y="{4:.1f}" text-anchor="end" fill="#555">{5}</text>)"
        "\n",
        py(v), left, plotRight, left - 6, py(v) + 4, tickLabel(v));
  }
  if (band > 0) {
    const double bandTop = std::max(py(std::min(band, y.hi)), static_cast<double>(top));
    svg += fmt::format(
        R"(<rect class="unresolved-band" x="{}" y="{:.1f}" width="{}" height="{:.1f}" fill="#dfe9f5" opacity="0.7"><title>unresolved: error within {}x the reference's convergence gap ({:.4f})</title></rect>)"
        R"(<text class="unresolved-label" x="{}" y="{:.1f}" fill="#3f6fb5" font-size="11">unresolved below {:.4f} ({}x the reference's convergence gap)</text>)"
        "\n",
        left, bandTop, plotRight - left, plotBottom - bandTop, kUnresolvedGapFactor, band / kUnresolvedGapFactor,
        left + 6, std::min(bandTop + 13, plotBottom - 4), band, kUnresolvedGapFactor);
  }
  svg += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#999"/>)"
                     "\n",
                     left, top, plotRight - left, plotBottom - top);
  svg += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle">GPU frame time (median, 95% CI; log)</text>)"
                     "\n",
                     (left + plotRight) / 2, plotBottom + 40);
  svg += fmt::format(
      R"svg(<text transform="translate(18 {}) rotate(-90)" text-anchor="middle">{} vs reference (± noise floor; log)</text>)svg"
      "\n",
      (top + plotBottom) / 2, escapeXml(errorColumnName(result)));

  // Each view's front as a line, fastest to slowest (one view unless a content axis varies).
  std::map<std::string, std::string> lines;
  for (std::size_t i : frontByTime(result)) {
    const auto& c = result.configurations[i];
    lines[viewOf(result, c)] += fmt::format("{:.1f},{:.1f} ", px(c.frameGpu.median), py(sweepError(c)));
  }
  for (const auto& [view, line] : lines) {
    svg += fmt::format(
        R"(<polyline class="front-line" points="{}" fill="none" stroke="#e8710a" stroke-width="2" stroke-dasharray="6 3"><title>{}</title></polyline>)"
        "\n",
        line, escapeXml(view.empty() ? std::string("the front") : "the front of " + view));
  }

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
        R"(<circle class="point{}" cx="{:.1f}" cy="{:.1f}" r="5" fill="{}" stroke="{}" stroke-width="1.5"><title>{}: {} [{}, {}], LDR-FLIP {:.5f}{}{}</title></circle>)"
        "\n",
        c.onFront ? " front" : "", cx, cy, c.onFront ? colour : "white", colour, escapeXml(c.configuration.label),
        escapeXml(durationLabel(c.frameGpu.median, 4)), escapeXml(durationLabel(c.frameGpu.lower, 4)),
        escapeXml(durationLabel(c.frameGpu.upper, 4)), e, c.onFront ? " (front)" : "",
        c.unresolved ? " (unresolved)" : "");
  }
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const PlacedLabel& l = labels[i];
    if (!l.shown) continue;
    const auto& c = result.configurations[i];
    if (l.leader) {
      // From the point's marker edge to the nearest point of the label's box.
      const double cx = requests[i].x, cy = requests[i].y;
      const double nx = std::clamp(cx, l.box.x0, l.box.x1), ny = std::clamp(cy, l.box.y0, l.box.y1);
      const double d = std::hypot(nx - cx, ny - cy);
      if (d > 7) {
        svg += fmt::format(R"(<line class="leader" x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#bbb"/>)"
                           "\n",
                           cx + (nx - cx) * 6 / d, cy + (ny - cy) * 6 / d, nx, ny);
      }
    }
    svg += fmt::format(R"(<text class="point-label{}{}" x="{:.1f}" y="{:.1f}" fill="{}"{}>{}</text>)"
                       "\n",
                       c.onFront ? " front" : "", l.numbered ? " numbered" : "", l.x, l.baseline,
                       c.onFront ? "#b35300" : "#666", c.onFront ? R"( font-weight="bold")" : "", escapeXml(l.text));
  }
  svg += fmt::format(
      R"(<circle cx="{0}" cy="{1}" r="5" fill="#e8710a"/><text x="{2}" y="{3}">on the Pareto front</text>)"
      R"(<circle cx="{0}" cy="{4}" r="5" fill="white" stroke="#888" stroke-width="1.5"/><text x="{2}" y="{5}">dominated</text>)"
      "\n",
      plotRight + 20, top + 10, plotRight + 32, top + 14, top + 30, top + 34);
  // The key of labels shown as numbers, under the axis title.
  for (std::size_t k = 0; k < numbered.size(); ++k) {
    const auto& c = result.configurations[numbered[k]];
    svg += fmt::format(R"(<text class="label-key" x="{}" y="{}" fill="{}">{}: {}</text>)"
                       "\n",
                       left + static_cast<int>(k % keyColumns) * (W - left) / keyColumns,
                       static_cast<int>(plotBottom) + 66 + static_cast<int>(k / keyColumns) * keyRow,
                       c.onFront ? "#b35300" : "#666", numbered[k] + 1, escapeXml(c.configuration.label));
  }
  return svg + "</svg>\n";
}

std::string passStackSvg(const SweepResult& result) {
  constexpr int row = 24, legendRow = 18, barsWidth = 590;
  std::vector<std::string> passes;  // every measured pass, first-seen order: one colour each
  double maxTotal = 0;
  std::size_t longestLabel = 0;
  for (const auto& c : result.configurations) {
    longestLabel = std::max(longestLabel, c.configuration.label.size());
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
  // The label column fits the longest label (about 7 px a character at 12 px bold sans-serif).
  const int label = std::clamp(static_cast<int>(longestLabel) * 7 + 12, 120, 600);
  const int W = std::max(860, label + barsWidth);
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
    svg += fmt::format(R"(<text x="{:.1f}" y="{}" fill="#555">{}</text>)"
                       "\n",
                       at + 4, yTop + 13, escapeXml(durationLabel(total, 3)));
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
    html +=
        fmt::format("{}<b>{}</b> ({}, LDR-FLIP {:.4f}{})", first ? "" : " &rarr; ", escapeXml(c.configuration.label),
                    escapeXml(durationLabel(c.frameGpu.median, 3)), sweepError(c), c.unresolved ? ", unresolved" : "");
    first = false;
  }
  html +=
      ".<br>Pick the fastest point on the front whose error you can accept; every other configuration is slower "
      "without being more accurate, or less accurate without being faster.</p>\n";

  html += "<h2>Time against error</h2>\n" + timeErrorSvg(result);
  html += "<ul class=\"note references\">\n";
  for (const std::string& line : referenceLines(result)) html += "<li>" + escapeXml(line) + "</li>\n";
  html += "</ul>\n";
  html += fmt::format(
      "<h2>Configurations</h2>\n<div class=\"table-scroll\"><table><tr><th># configuration</th><th>front</th><th>GPU "
      "frame ms</th><th>95% CI</th>"
      "<th>frames</th><th>{}</th><th>HDR-FLIP</th><th>RMSE</th><th>PSNR dB</th><th>NaN/Inf</th><th>bias</th>"
      "<th>dominated by</th></tr>\n",
      escapeXml(errorColumnName(result)));
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    const auto& c = result.configurations[i];
    // Dominating configurations by number (their labels on hover): a list of long labels made the
    // rows of a big grid several lines tall.
    std::string dominatedBy;
    for (std::size_t d : c.dominatedBy) {
      dominatedBy += fmt::format(R"({}<span title="{}">#{}</span>)", dominatedBy.empty() ? "" : ", ",
                                 escapeXml(result.configurations[d].configuration.label), d + 1);
    }
    html += fmt::format(
        "<tr{}><td>#{} {}</td><td>{}</td><td>{:.4f}</td><td>[{:.4f}, "
        "{:.4f}]</td><td>{}</td><td>{}{}</td><td>{}</td><td>{:.5f}</td>"
        "<td>{}</td><td>{}</td><td>{}</td><td class=\"dominated\">{}</td></tr>\n",
        c.onFront ? " class=\"front\"" : "", i + 1, escapeXml(c.configuration.label), c.onFront ? "front" : "",
        c.frameGpu.median, c.frameGpu.lower, c.frameGpu.upper, c.frameGpu.n,
        c.display.flip ? fmt::format("{:.5f}", c.display.flip->mean) : "-",
        c.unresolved ? R"( <span class="unresolved" title="within the reference's convergence gap">unresolved</span>)"
                     : "",
        c.hdr.flip ? fmt::format("{:.5f}", c.hdr.flip->mean) : "-", c.display.rmse,
        std::isfinite(c.display.psnr) ? fmt::format("{:.2f}", c.display.psnr) : "&infin;",
        c.display.nonFiniteTest + c.hdr.nonFiniteTest,
        c.bias ? fmt::format(R"(<span title="{}">{:.4f}</span>)",
                             escapeXml(result.references[c.reference].biases[*c.bias].label),
                             result.references[c.reference].biases[*c.bias].gap())
               : "-",
        dominatedBy);
  }
  html += "</table></div>\n<h2>Per-pass GPU time</h2>\n" + passStackSvg(result);

  html += "<h2>Frames and LDR-FLIP against the reference</h2>\n<div class=\"gallery\">\n";
  for (std::size_t r = 0; r < result.references.size(); ++r) {
    const auto& ref = result.references[r];
    html += fmt::format("<figure>{}<figcaption>reference {} ({}; two renders {})</figcaption></figure>\n",
                        imgTag(ref.images.display, "reference"), r + 1, sizeText(ref.workload, ref.images),
                        ref.identical ? "bit-identical" : "differ");
  }
  for (const auto& c : result.configurations) {
    html += fmt::format(
        "<figure><div class=\"pair\">{}{}</div><figcaption>{}{}: {}, LDR-FLIP {:.4f}</figcaption></figure>\n",
        imgTag(c.images.display, c.configuration.label), imgTag(c.heatMap, "FLIP " + c.configuration.label),
        c.onFront ? "<b>front</b> " : "", escapeXml(c.configuration.label),
        escapeXml(durationLabel(c.frameGpu.median, 3)), sweepError(c));
  }
  html += "</div>\n<h2>Method</h2>\n<p>" + escapeXml(sweepMethodNote(result) + pathMethodNote(result)) +
          "</p>\n</body></html>\n";
  return html;
}

}  // namespace fgb::harness
