#include <fgb/harness/report/html_util.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/stats/stats.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fgb::harness {
namespace {

constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:900px;margin:2em auto;color:#222}"
    "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
    "td:first-child,th:first-child{text-align:left}.bad{color:#c0392b;font-weight:bold}.ok{color:#2e7d32}"
    ".note{color:#555}"
    "figure{margin:0}figcaption{color:#555;font-size:90%}img.shot{width:100%;height:auto;border:1px solid #ccc}"
    ".trio{display:flex;gap:8px}.trio figure{flex:1;min-width:0}#flipper button{font-size:100%}"
    ".strip{display:flex;flex-wrap:wrap;gap:6px}.strip img{display:block;width:160px}.pass.first{outline:3px solid "
    "#c0392b}";

// Flips #flip-view between the reference and the test image (the sources are those of the images
// above it, so each picture is in the file once).
constexpr const char* kFlipScript =
    "(function(){var v=document.getElementById('flip-view'),b=document.getElementById('flip-toggle'),"
    "l=document.getElementById('flip-label'),r=document.getElementById('golden-reference'),"
    "t=document.getElementById('frame'),test=false;"
    "function show(){v.src=(test?t:r).src;v.dataset.showing=test?'test':'reference';l.textContent=test?'test (this run)':'reference (golden)';"
    "b.textContent=test?'Show reference':'Show test';}"
    "b.addEventListener('click',function(){test=!test;show();});show();"
    "document.getElementById('flipper').hidden=false;})();";

std::string verdictSpan(const std::string& verdict) {
  const char* cls = verdict == "fail" ? "bad" : (verdict == "pass" ? "ok" : "note");
  return fmt::format(R"(<span class="{}">{}</span>)", cls, escapeXml(verdict));
}

std::string isolatedTableHtml(const RunResult& run) {
  std::string html = "<p class=\"note\">" + escapeXml(isolatedCostNote(run)) +
                     "</p>\n<table><tr><th>pass</th><th>span</th><th>isolated</th><th>critical path</th></tr>\n";
  for (const auto& p : run.passes) {
    if (p.culled || !p.hasIsolated()) continue;
    html +=
        fmt::format("<tr><td>{}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</td></tr>\n", escapeXml(p.name), p.gpu.median,
                    p.isolated.median, p.criticalShare >= 0.0 ? fmt::format("{:.1f}%", 100.0 * p.criticalShare) : "–");
  }
  return html + "</table>\n";
}

std::string passRows(const RunResult& run) {
  std::string rows;
  auto cells = [](const Summary& s) {
    return fmt::format("<td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{:.4f}</td><td>{}</td>",
                       s.median, s.p5, s.p95, s.mean, s.min, s.max, s.n);
  };
  for (const auto& p : run.passes) {
    rows += fmt::format("<tr><td>{}</td><td>{}</td>{}<td>{}</td></tr>\n", escapeXml(p.name), escapeXml(p.queue),
                        p.culled ? std::string(R"(<td colspan="7">culled</td>)") : cells(p.gpu),
                        p.unstable ? R"(<span class="bad">unstable</span>)" : "");
  }
  rows += fmt::format("<tr><th>frame (GPU)</th><td></td>{}<td></td></tr>\n", cells(run.frameGpu));
  rows += fmt::format("<tr><th>frame (CPU)</th><td></td>{}<td></td></tr>\n", cells(run.frameCpu));
  return rows;
}

std::string budgetHtml(const RunResult& run) {
  if (!run.budget) return "<p class=\"note\">No budget given.</p>\n";
  std::string out = fmt::format("<p>{}: {}</p>\n<ul>\n", escapeXml(run.budget->file), verdictSpan(run.budget->verdict));
  for (const auto* line : run.budget->failing()) {
    out += line->status == "missing"
               ? fmt::format("<li>{}: not measured (budget {:.3f} ms)</li>\n", escapeXml(line->pass), line->budgetMs)
               : fmt::format("<li>{}: {:.4f} ms against {:.3f} ms, over by {:.4f} ms ({:+.1f}%)</li>\n", escapeXml(line->pass),
                             *line->measuredMs, line->budgetMs, line->overMs(), line->overPercent());
  }
  for (const auto& w : run.budget->warnings) out += "<li class=\"note\">" + escapeXml(w) + "</li>\n";
  return out + "</ul>\n";
}

std::string goldenHtml(const RunResult& run) {
  if (!run.golden) return "<p class=\"note\">No golden compared.</p>\n";
  std::string out = fmt::format("<p>{}: {}</p>\n<table><tr><th>image</th><th>max abs</th><th>RMSE</th><th>PSNR dB</th>"
                                "<th>share over</th><th>FLIP mean</th><th>FLIP p99</th><th>NaN/Inf</th><th>failures</th><th>heat map</th></tr>\n",
                                escapeXml(run.golden->file), verdictSpan(run.golden->verdict));
  for (const auto& image : run.golden->images) {
    const auto& m = image.metrics;
    std::string failures;
    for (const auto& f : image.failures) failures += (failures.empty() ? "" : "; ") + f;
    // checkGolden writes the heat map of each failing image next to this report (run_outputs.cpp).
    const char* heatMap = image.kind == "hdr" ? "golden-diff-hdr.png" : "golden-diff.png";
    const std::string heatMapCell = image.failures.empty() ? "–" : fmt::format(R"(<a href="{0}">{0}</a>)", heatMap);
    out += fmt::format("<tr><td>{}</td><td>{:.5f}</td><td>{:.5f}</td><td>{}</td><td>{:.4f}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                       image.kind, m.maxAbsError, m.rmse, std::isfinite(m.psnr) ? fmt::format("{:.2f}", m.psnr) : "∞",
                       m.shareOverThreshold, m.flip ? fmt::format("{:.5f}", m.flip->mean) : "–",
                       m.flip ? fmt::format("{:.5f}", m.flip->p99) : "–", m.nonFiniteReference + m.nonFiniteTest,
                       escapeXml(failures.empty() ? "none" : failures), heatMapCell);
  }
  return out + "</table>\n";
}

std::string figure(const std::string& id, std::span<const uint8_t> png, const ReportImages& images, const std::string& alt,
                   const std::string& captionHtml) {
  return fmt::format(R"(<figure><img class="shot" id="{}" src="{}" width="{}" height="{}" alt="{}"><figcaption>{}</figcaption></figure>)"
                     "\n",
                     id, pngDataUri(png), images.width, images.height, escapeXml(alt), captionHtml);
}

// Where the difference enters: each compared pass's image over its heat map, in declaration order.
std::string passStripHtml(const RunResult& run, const ReportImages& images) {
  std::string html = "<p id=\"first-difference\">" + escapeXml(run.firstDifference) + "</p>\n<div class=\"strip\">\n";
  for (const auto& thumb : images.passStrip) {
    const char* mark = thumb.firstDifference ? "first difference" : thumb.differs ? "differs" : "matches";
    html += fmt::format(R"(<figure class="pass {}"><img src="{}" alt="{}">)", thumb.firstDifference ? "first" : "",
                        pngDataUri(thumb.png), escapeXml(thumb.file));
    if (!thumb.heatMap.empty()) html += fmt::format(R"(<img src="{}" alt="heat map">)", pngDataUri(thumb.heatMap));
    html += fmt::format("<figcaption>{}<br>{}</figcaption></figure>\n", escapeXml(thumb.file), mark);
  }
  return html + "</div>\n";
}

// The frame inline; with a golden, reference | test | heat map side by side and a flip view.
std::string picturesHtml(const RunResult& run, const ReportImages& images) {
  const std::string files = "<a href=\"frame.png\">frame.png</a> (tone-mapped) · <a href=\"frame.exr\">frame.exr</a> (linear HDR)";
  if (images.frame.empty()) return "<p>Last frame: " + files + "</p>\n";
  if (images.reference.empty()) return figure("frame", images.frame, images, "last frame", "Last frame: " + files);
  std::string flipMean;
  if (run.golden && !run.golden->images.empty() && run.golden->images[0].metrics.flip) {
    flipMean = fmt::format(", mean {:.5f}", run.golden->images[0].metrics.flip->mean);
  }
  std::string html = "<div class=\"trio\">\n";
  html += figure("golden-reference", images.reference, images, "reference", "Reference (golden)");
  html += figure("frame", images.frame, images, "test", "Test (this run): " + files);
  if (!images.heatMap.empty()) html += figure("golden-heatmap", images.heatMap, images, "FLIP heat map", "FLIP heat map" + flipMean);
  html += "</div>\n";
  html += fmt::format(R"(<div id="flipper" hidden><p><button id="flip-toggle" type="button">Show test</button> showing <b id="flip-label">reference (golden)</b></p>)"
                      R"(<img class="shot" id="flip-view" width="{}" height="{}" alt="reference or test, as the button flips them"></div>)"
                      "\n<script>{}</script>\n",
                      images.width, images.height, kFlipScript);
  return html;
}

// Along a camera path: thumbnails of the slowest frames (rendered alone at their path times).
std::string slowestFramesHtml(const RunResult& run, const ReportImages& images) {
  if (run.slowestFrames(1).empty()) return "";
  std::string html = fmt::format(
      "<h2>Slowest frames along the camera path</h2>\n<p>GPU frame p95 {:.4f} ms, p99 {:.4f} ms, worst {:.4f} ms over {} "
      "frames ({:g} s to {:g} s).</p>\n<div class=\"trio\">\n",
      run.frameGpu.p95, run.frameGpu.p99, run.frameGpu.max, run.framePathTimeS.size(), run.framePathTimeS.front(),
      run.framePathTimeS.back());
  for (const auto& slow : images.slowest) {
    html += fmt::format(R"(<figure><img class="shot" src="{}" width="{}" height="{}" alt="frame {}"><figcaption>frame {} at {:g} s: {:.4f} ms (<code>--set camera.time={}</code>)</figcaption></figure>)"
                        "\n",
                        pngDataUri(slow.png), images.width / 2, images.height / 2, slow.frame, slow.frame, slow.pathTimeS,
                        run.frameGpuMs[slow.frame], slow.pathTimeS);
  }
  return html + "</div>\n";
}

// On a path that draws clusters: what the LOD cut chose, beside the clusters themselves.
std::string debugViewsHtml(const RunResult& run, const ReportImages& images) {
  if (images.debugViews.empty()) return "";
  const auto threshold = run.stats.find("vis_lod_threshold_px");
  const auto meshletThreshold = run.stats.find("meshlet_lod_threshold_px");
  const double px = threshold != run.stats.end()          ? threshold->second
                    : meshletThreshold != run.stats.end() ? meshletThreshold->second
                                                          : 0.0;
  std::string html = fmt::format(
      "<h2>Clusters and their LOD levels</h2>\n<p>The frame again with <code>debug.view=lod</code> (level 0, full "
      "detail, blue; then cyan, green, yellow, orange, red, magenta) and <code>debug.view=clusters</code>; the cut "
      "keeps each cluster's error under {:g} scene pixels (<code>render.lod_error</code>).</p>\n<div class=\"trio\">\n",
      px);
  for (const auto& view : images.debugViews) {
    html += fmt::format(
        R"(<figure><img class="shot" src="{}" width="{}" height="{}" alt="debug.view={}"><figcaption><a href="debug-{}.png"><code>debug.view={}</code></a></figcaption></figure>)"
        "\n",
        pngDataUri(view.png), images.width / 2, images.height / 2, view.view, view.view, view.view);
  }
  return html + "</div>\n";
}

}  // namespace

std::string htmlReport(const RunResult& run, const ReportImages& images) {
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n";
  html += fmt::format("<title>fgbench report: {}</title>\n<style>{}</style></head><body>\n", escapeXml(run.scene), kStyle);
  html += fmt::format("<h1>fgbench report: {}</h1>\n", escapeXml(run.scene));
  html += fmt::format("<p>{} ({}), driver {}, Vulkan {}<br>{}×{}, MSAA: {}, {} measured frames after {} warm-up; tool {}</p>\n",
                      escapeXml(run.device.name), escapeXml(run.device.type), escapeXml(run.device.driver),
                      escapeXml(run.device.apiVersion), run.config.width, run.config.height, msaaLabel(run.config.msaa),
                      run.config.frames, run.config.warmup, escapeXml(run.toolVersion));
  html += "<p class=\"note\">" + escapeXml(timestampSourceNote(run.device)) + "</p>\n";
  html += "<h2>Frame</h2>\n" + picturesHtml(run, images);
  html += "<p>Frame graph: <a href=\"graph.dot\">graph.dot</a>, <a href=\"graph-full.dot\">graph-full.dot</a></p>\n";
  html += "<h2>Passes against budget</h2>\n" + passBarsSvg(run);
  html += "<h2>Frame time series</h2>\n" + frameSeriesSvg(run);
  html += slowestFramesHtml(run, images);
  html += debugViewsHtml(run, images);
  html += "<h2>Queue timeline</h2>\n" + queueTimelineSvg(run);
  html += "<h2>Timings (ms)</h2>\n<table><tr><th>pass</th><th>queue</th><th>median</th><th>p5</th><th>p95</th><th>mean</th>"
          "<th>min</th><th>max</th><th>n</th><th>spread</th></tr>\n" + passRows(run) + "</table>\n";
  html += fmt::format("<p class=\"note\">unstable: (p95 − p5) / median above {:g}; read such medians with care.</p>\n",
                      kDefaultUnstableSpread);
  html += "<p class=\"note\">" + escapeXml(hostOverheadNote(run)) + "</p>\n";
  html += "<p class=\"note\">" + escapeXml(wallClockNote(run)) + "</p>\n";
  if (const std::string async = asyncComputeNote(run); !async.empty())
    html += "<p class=\"note\">" + escapeXml(async) + "</p>\n";
  if (run.isolatedFrames > 0) html += "<h2>Span, isolated cost and critical path</h2>\n" + isolatedTableHtml(run);
  html += "<h2>Budget</h2>\n" + budgetHtml(run);
  html += "<h2>Golden image</h2>\n" + goldenHtml(run);
  if (!run.firstDifference.empty()) html += "<h2>Per-pass goldens</h2>\n" + passStripHtml(run, images);
  return html + "</body></html>\n";
}

}  // namespace fgb::harness
