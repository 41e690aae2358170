// stress.json, stress.md and stress.html (inline SVG: error against rung on a log axis; the first
// failing rung's frame beside its heat map).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fgb/core/atomic_file.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/report/html_util.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/stress/stress.hpp>

namespace fgb::harness {
namespace {

nlohmann::json toJson(const render::NonFiniteCounts& c) {
  return {{"pass", c.pass}, {"nan", c.nan}, {"inf", c.inf}, {"over_half_max", c.overHalfMax}};
}

nlohmann::json thresholdsJson(const StressThresholds& t) {
  return {{"flip_mean", t.flipMean},
          {"pixel_share", t.pixelShare},
          {"max_abs", std::isfinite(t.maxAbs) ? nlohmann::json(t.maxAbs) : nlohmann::json(nullptr)},
          {"non_finite", t.nonFinite},
          {"over_half_max", t.overHalfMax}};
}

double flipOf(const std::optional<ImageMetrics>& m) {
  return m && m->flip ? m->flip->mean : 0.0;
}

// FLIP mean, max abs error, share of pixels over 2/255 (against the baseline).
std::array<std::string, 3> metricValues(const StressRungOutcome& r) {
  if (!r.display) return {"–", "–", "–"};
  return {fmt::format("{:.5f}", flipOf(r.display)), fmt::format("{:.4f}", r.display->maxAbsError),
          fmt::format("{:.2f}%", 100.0 * r.display->shareOverThreshold)};
}

std::string nonFiniteCell(const StressRungOutcome& r) {
  for (const auto& c : r.nonFinite)
    if (c.bad()) return fmt::format("{}: {}/{}/{}", c.pass, c.nan, c.inf, c.overHalfMax);
  return r.rendered ? "0" : "–";
}

// Tick labels of the stress chart, whose rungs span up to 13 decades (offsets 1e7, near planes 1e-6):
// 3 significant digits, in exponent form where shorter, as the ladders are written.
std::string stressTickLabel(double v) { return fmt::format("{:.3g}", v); }

// Error (FLIP mean) against the rung value, both on log axes; failing rungs in red.
std::string errorSvg(const StressResult& result) {
  std::vector<const StressRungOutcome*> points;
  for (size_t i = 1; i < result.rungs.size(); ++i)
    if (result.rungs[i].rung.axis > 0) points.push_back(&result.rungs[i]);
  if (points.empty()) return "<p class=\"note\">No rung with a positive value to plot.</p>";
  double xlo = points.front()->rung.axis, xhi = xlo;
  double ylo = 1e-6, yhi = std::max(result.ladder.thresholds.flipMean, 1e-4);
  for (const auto* p : points) {
    xlo = std::min(xlo, p->rung.axis);
    xhi = std::max(xhi, p->rung.axis);
    yhi = std::max(yhi, flipOf(p->display));
  }
  const LogAxis x = paddedLogAxis(xlo, xhi), y = paddedLogAxis(ylo, yhi);
  const int w = 720, h = 320, left = 70, right = 20, top = 20, bottom = 50;
  std::string svg = fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}">)", w, h);
  svg += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#999"/>)", left, top,
                     w - left - right, h - top - bottom);
  const auto px = [&](double v) { return x.at(v, left, w - right); };
  const auto py = [&](double v) { return y.at(std::max(v, ylo), h - bottom, top); };
  for (double t : x.ticks()) {
    svg += fmt::format(R"(<text x="{:.1f}" y="{}" font-size="11" text-anchor="middle">{}</text>)", px(t),
                       h - bottom + 16, stressTickLabel(t));
  }
  for (double t : y.ticks()) {
    svg += fmt::format(R"(<text x="{}" y="{:.1f}" font-size="11" text-anchor="end">{}</text>)", left - 6, py(t) + 4,
                       stressTickLabel(t));
  }
  const double limit = py(result.ladder.thresholds.flipMean + flipOf(result.noise));
  svg += fmt::format(R"(<line x1="{}" x2="{}" y1="{:.1f}" y2="{:.1f}" stroke="#c0392b" stroke-dasharray="4 3"/>)", left,
                     w - right, limit, limit);
  svg += fmt::format(R"(<text x="{}" y="{:.1f}" font-size="11" fill="#c0392b" text-anchor="end">threshold</text>)",
                     w - right - 4, limit - 4);
  std::string previousSeries;
  std::string path;
  for (const auto* p : points) {
    const double cx = px(p->rung.axis), cy = py(flipOf(p->display));
    path += fmt::format("{}{:.1f},{:.1f} ", path.empty() || p->rung.series != previousSeries ? "M" : "L", cx, cy);
    previousSeries = p->rung.series;
    svg += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="5" fill="{}"><title>{}: {}</title></circle>)", cx, cy,
                       p->pass ? "#3f6fb5" : "#c0392b", escapeXml(p->rung.value),
                       escapeXml(p->pass ? "pass" : p->failure));
  }
  svg += fmt::format(R"(<path d="{}" fill="none" stroke="#3f6fb5"/>)", path);
  svg += fmt::format(R"(<text x="{}" y="{}" font-size="12" text-anchor="middle">{} (log)</text>)",
                     (left + w - right) / 2, h - 12, escapeXml(result.ladder.key));
  svg += fmt::format(R"svg(<text x="14" y="{}" font-size="12" transform="rotate(-90 14 {})" text-anchor="middle">)svg"
                     "FLIP mean vs baseline (log)</text>",
                     (top + h - bottom) / 2, (top + h - bottom) / 2);
  return svg + "</svg>";
}

}  // namespace

nlohmann::json toJson(const StressResult& result) {
  nlohmann::json rungs = nlohmann::json::array();
  for (const auto& r : result.rungs) {
    nlohmann::json counts = nlohmann::json::array();
    for (const auto& c : r.nonFinite) counts.push_back(toJson(c));
    rungs.push_back({{"value", r.rung.value},
                     {"axis", r.rung.axis},
                     {"series", r.rung.series},
                     {"knobs", r.rung.knobs},
                     {"rendered", r.rendered},
                     {"error", r.error},
                     {"display", r.display ? toJson(*r.display) : nlohmann::json(nullptr)},
                     {"non_finite", counts},
                     {"pass", r.pass},
                     {"failure", r.failure}});
  }
  const auto first = result.firstFailure();
  return {{"schema", 1},
          {"tool_version", result.toolVersion},
          {"scene", result.scene},
          {"device", {{"name", result.device.name}, {"driver", result.device.driver}, {"type", result.device.type}}},
          {"ladder",
           {{"name", result.ladder.name},
            {"key", result.ladder.key},
            {"description", result.ladder.description},
            {"compare_images", result.ladder.compareImages},
            {"thresholds", thresholdsJson(result.ladder.thresholds)}}},
          {"noise", toJson(result.noise)},
          {"rungs", rungs},
          {"verdict", first ? "fail" : "pass"},
          {"first_failure", first ? nlohmann::json(result.rungs[*first].rung.value) : nlohmann::json(nullptr)},
          {"summary", result.summary()},
          {"wall_ms", result.wallMs}};
}

std::string stressMarkdown(const StressResult& result) {
  const StressThresholds& t = result.ladder.thresholds;
  std::string out = fmt::format("# fgbench stress: {} — ladder {}\n\n", result.scene, result.ladder.name);
  out += fmt::format("**{}**\n\n", result.summary());
  out += fmt::format("- Device: {} ({})\n- Varies: {} — {}\n", result.device.name, result.device.driver,
                     result.ladder.key, result.ladder.description);
  out += fmt::format("- Baseline: rung {} rendered twice: noise FLIP mean {:.6f}, pixels over 2/255 {:.3f}%\n",
                     result.rungs.front().rung.value, result.noise.flip ? result.noise.flip->mean : 0.0,
                     100.0 * result.noise.shareOverThreshold);
  out += result.ladder.compareImages
             ? fmt::format(
                   "- A rung fails when a pass writes a NaN or Inf{}, or against the baseline: "
                   "FLIP mean > {:g} + noise, pixels over 2/255 > {:g}% + noise{}\n",
                   t.overHalfMax ? " (or > 32752)" : "", t.flipMean, 100 * t.pixelShare,
                   std::isfinite(t.maxAbs) ? fmt::format(", max abs error > {:g}", t.maxAbs) : "")
             : fmt::format("- A rung fails when a pass writes a NaN or Inf{}; the image changes by design\n",
                           t.overHalfMax ? " (or > 32752)" : "");
  out +=
      "\n| rung | FLIP mean | max abs | pixels > 2/255 | non-finite (pass: NaN/Inf/>32752) | verdict |\n"
      "|---|---:|---:|---:|---|---|\n";
  for (const auto& r : result.rungs) {
    const auto m = metricValues(r);
    out += fmt::format("| {} | {} | {} | {} | {} | {} |\n", r.rung.value, m[0], m[1], m[2], nonFiniteCell(r),
                       r.pass ? "pass" : "**fail**: " + r.failure);
  }
  return out;
}

std::string stressHtml(const StressResult& result) {
  std::string html =
      "<!doctype html><html><head><meta charset=\"utf-8\"><title>fgbench stress</title><style>"
      "body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
      "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 8px}"
      ".fail{background:#fdecea}.pair{display:flex;gap:6px}img{image-rendering:pixelated;"
      "border:1px solid #ccc}.summary{font-size:1.1em;padding:.6em 1em;border-left:4px solid #3f6fb5}"
      "</style></head><body>";
  html += fmt::format("<h1>stress: {} — {}</h1><p class=\"summary\">{}</p>", escapeXml(result.scene),
                      escapeXml(result.ladder.name), escapeXml(result.summary()));
  html += "<p>" + escapeXml(result.ladder.description) + "</p>";
  if (result.ladder.compareImages) html += errorSvg(result);
  html +=
      "<table><tr><th>rung</th><th>FLIP mean</th><th>max abs</th><th>pixels &gt; 2/255</th><th>non-finite</th>"
      "<th>verdict</th></tr>";
  for (const auto& r : result.rungs) {
    const auto m = metricValues(r);
    html += fmt::format("<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                        r.pass ? "" : " class=\"fail\"", escapeXml(r.rung.value), m[0], m[1], m[2],
                        escapeXml(nonFiniteCell(r)), escapeXml(r.pass ? "pass" : "fail: " + r.failure));
  }
  html += "</table>";
  const auto first = result.firstFailure();
  if (first && result.rungs[*first].images.display.width > 0 && result.rungs.front().images.display.width > 0) {
    const auto& r = result.rungs[*first];
    html += fmt::format(
        "<h2>First failing rung: {}</h2><div class=\"pair\"><figure>{}<figcaption>frame</figcaption>"
        "</figure>",
        escapeXml(r.rung.value), imgTag(r.images.display, "frame of rung " + r.rung.value, 480));
    if (r.heatMap.width > 0) {
      html += fmt::format("<figure>{}<figcaption>FLIP against the baseline</figcaption></figure>",
                          imgTag(r.heatMap, "heat map of rung " + r.rung.value, 480));
    }
    html += fmt::format("<figure>{}<figcaption>baseline {}</figcaption></figure></div>",
                        imgTag(result.rungs.front().images.display, "baseline", 480),
                        escapeXml(result.rungs.front().rung.value));
  }
  return html + "</body></html>\n";
}

void writeStressOutputs(const std::filesystem::path& dir, const StressResult& result) {
  std::filesystem::create_directories(dir);
  writeFileAtomic(dir / "stress.json", dumpJson(toJson(result)));
  writeFileAtomic(dir / "stress.md", stressMarkdown(result));
  writeFileAtomic(dir / "stress.html", stressHtml(result));
}

}  // namespace fgb::harness
