// sweep.json, sweep.csv, sweep.md and the terminal table.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/report/html_util.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/harness/sweep_report/sweep_report.hpp>

namespace fgb::harness {
namespace {

nlohmann::json knobsJson(const std::map<std::string, std::string>& knobs) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : knobs) j[k] = v;
  return j;
}

uint32_t msaaUsed(const ConfigurationOutcome& c) {
  const auto it = c.run.stats.find("msaa");
  return it != c.run.stats.end() ? static_cast<uint32_t>(it->second) : c.configuration.workload.msaa;
}

nlohmann::json configJson(const render::WorkloadConfig& w, const RenderedImages& images) {
  const auto [width, height] = renderedSize(w, images);
  return {{"width", width},
          {"height", height},
          {"msaa_requested", w.msaa},
          {"knobs", knobsJson(w.knobs)}};
}

nlohmann::json intervalJson(const MedianInterval& ci, const Summary& s) {
  return {{"median", ci.median}, {"ci_low", ci.lower}, {"ci_high", ci.upper}, {"ci_coverage", ci.coverage},
          {"n", ci.n},           {"p5", s.p5},         {"p95", s.p95},        {"mean", s.mean},
          {"min", s.min},        {"max", s.max}};
}

nlohmann::json passesJson(const RunResult& run) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : run.passes) {
    passes.push_back({{"name", p.name},
                      {"queue", p.queue},
                      {"culled", p.culled},
                      {"median_ms", p.gpu.median},
                      {"p5_ms", p.gpu.p5},
                      {"p95_ms", p.gpu.p95},
                      {"n", p.gpu.n}});
  }
  return passes;
}

nlohmann::json checkJson(const ReferenceCheck& check) {
  return {
      {"label", check.label},
      {"config", {{"msaa_requested", check.workload.msaa}, {"knobs", knobsJson(check.workload.knobs)}}},
      {"gap", check.gap()},
      {"display", toJson(check.display)},
      {"hdr", toJson(check.hdr)},
      {"wall_ms", {{"open", check.wall.openMs}, {"frames", check.wall.framesMs}, {"readback", check.wall.readbackMs}}}};
}

// The configuration's cost-only knobs' bias: their converged render against the reference.
nlohmann::json biasJson(const SweepResult& result, const ConfigurationOutcome& c) {
  if (!c.bias) return nullptr;
  const ReferenceCheck& b = result.references[c.reference].biases[*c.bias];
  return {{"label", b.label}, {"ldr_flip_mean", b.gap()}};
}

// The configuration's errors along the camera path (null for a still scene): each path time's
// metrics, their mean and the worst (the front judges the mean).
nlohmann::json pathErrorJson(const ConfigurationOutcome& c) {
  if (c.pathErrors.empty()) return nullptr;
  nlohmann::json times = nlohmann::json::array();
  for (const PathTimeError& e : c.pathErrors)
    times.push_back({{"time_s", e.timeS}, {"display", toJson(e.display)}, {"hdr", toJson(e.hdr)}});
  return {{"times", times},
          {"ldr_flip_mean", c.pathErrorMean()},
          {"ldr_flip_worst", c.pathErrorWorst()},
          {"worst_time_s", c.pathErrorWorstTime()}};
}

nlohmann::json configurationJson(const SweepResult& result, const ConfigurationOutcome& c) {
  nlohmann::json point = nlohmann::json::object();
  for (const auto& [k, v] : c.configuration.point) point[k] = v;
  nlohmann::json dominatedBy = nlohmann::json::array();
  for (std::size_t d : c.dominatedBy) dominatedBy.push_back(result.configurations[d].configuration.label);
  nlohmann::json config = configJson(c.configuration.workload, c.images);
  config["msaa"] = msaaUsed(c);
  return {{"label", c.configuration.label},
          {"point", point},
          {"config", config},
          {"reference", c.reference},
          {"frame_gpu_ms", intervalJson(c.frameGpu, c.run.frameGpu)},
          {"frame_cpu_ms", {{"median", c.run.frameCpu.median}, {"p5", c.run.frameCpu.p5}, {"p95", c.run.frameCpu.p95}}},
          {"stable", c.stable},
          {"passes", passesJson(c.run)},
          {"error", {{"display", toJson(c.display)}, {"hdr", toJson(c.hdr)}}},
          {"path_error", pathErrorJson(c)},
          {"front", c.onFront},
          {"unresolved", c.unresolved},
          {"bias", biasJson(result, c)},
          {"dominated_by", dominatedBy},
          {"wall_ms",
           {{"open", c.wall.openMs},
            {"warmup", c.wall.warmupMs},
            {"warmup_frames", c.wall.warmupFrames},
            {"measure", c.wall.measureMs},
            {"measured_frames", c.run.frameGpuMs.size()},
            {"rewarm_frames", c.wall.rewarmFrames},
            {"visits", c.wall.visits},
            {"metrics", c.wall.metricsMs}}},
          {"samples", {{"frame_gpu_ms", c.run.frameGpuMs}}}};
}

nlohmann::json referenceJson(const ReferenceOutcome& r) {
  nlohmann::json renders = nlohmann::json::array();
  for (const auto& w : r.renders)
    renders.push_back({{"open", w.openMs}, {"frames", w.framesMs}, {"readback", w.readbackMs}});
  nlohmann::json biases = nlohmann::json::array();
  for (const auto& b : r.biases) biases.push_back(checkJson(b));
  return {{"config", configJson(r.workload, r.images)},
          {"repeat_identical", r.identical},
          {"convergence", r.convergence ? checkJson(*r.convergence) : nlohmann::json(nullptr)},
          {"unresolved_below", kUnresolvedGapFactor * r.convergenceGap()},
          {"biases", biases},
          {"noise", {{"display", toJson(r.repeatDisplay)}, {"hdr", toJson(r.repeatHdr)}}},
          {"render_ms", r.renderMs},
          {"renders_ms", renders}};
}

nlohmann::json shardJson(const SweepResult& result) {
  if (!result.shard) return nullptr;
  return {{"index", result.shard->index},
          {"count", result.shard->count},
          {"grid_size", result.shard->gridSize},
          {"grid_indices", result.shard->gridIndices}};
}

// A shard's images, for sweep-merge's page, at the size the page shows them (full-size 1080p PNGs
// took a shard 6 s to encode on the H200's host; thumbnails 0.2 s): images/config-G.png and
// heat-G.png by grid place G, images/reference-R.png by the shard's reference R (1-based).
void writeShardImages(const std::filesystem::path& dir, const SweepResult& result) {
  const auto images = dir / "images";
  std::error_code ec;
  std::filesystem::create_directories(images, ec);
  if (ec) throw InputError(images.string() + ": cannot create (" + ec.message() + ")");
  for (std::size_t r = 0; r < result.references.size(); ++r)
    writePng(images / fmt::format("reference-{}.png", r + 1),
             shrinkToWidth(result.references[r].images.display, kThumbnailWidth));
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    const std::size_t g = result.shard->gridIndices[i] + 1;
    const auto& c = result.configurations[i];
    writePng(images / fmt::format("config-{}.png", g), shrinkToWidth(c.images.display, kThumbnailWidth));
    writePng(images / fmt::format("heat-{}.png", g), shrinkToWidth(c.heatMap, kThumbnailWidth));
  }
}

nlohmann::json methodJson(const SweepResult& result) {
  nlohmann::json stable = nullptr;
  if (result.untilStable) {
    stable = {{"relative_half_width", result.untilStable->relativeHalfWidth},
              {"min_frames", result.untilStable->minFrames},
              {"batch_frames", result.untilStable->batchFrames},
              {"check_frames", result.stableCheckFrames}};
  }
  nlohmann::json roles = nlohmann::json::object();
  for (const auto& [key, role] : result.roles) roles[key] = role;
  return {{"time", "median GPU frame time; 95% distribution-free order-statistic interval (exact binomial)"},
          {"error", result.lookKeys.empty()
                        ? "LDR-FLIP mean of the tone-mapped frame against the reference"
                        : "LDR-FLIP mean of the tone-mapped frame against the reference, which keeps the scene's own "
                          "value of the varied look knob(s): the change from the scene's look"},
          {"error_column", errorColumnName(result)},
          {"look_knobs", result.lookKeys},
          {"roles", roles},
          {"reference_ssaa", result.referenceRules.ssaa},
          {"unresolved_factor", kUnresolvedGapFactor},
          {"dominance",
           "significantly faster or equal (one-sided Mann-Whitney U, alpha) and error <= other's + "
           "error_floor, strictly better in one"},
          {"alpha", result.alpha},
          {"error_floor", result.errorFloor},
          {"seed", result.seed},
          {"rounds", result.rounds},
          {"frame_cap", result.frameCap},
          {"warmup_frames", result.warmupFrames},
          {"rewarm_frames", result.rewarmFrames},
          {"until_stable", stable},
          {"stop_reason", result.stopReason},
          {"path_times_s", result.pathTimes},
          {"note", sweepMethodNote(result) + pathMethodNote(result)}};
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string flipText(const ImageMetrics& m) {
  return m.flip ? fmt::format("{:.4f}", m.flip->mean) : "-";
}
std::string psnrText(const ImageMetrics& m) {
  return std::isfinite(m.psnr) ? fmt::format("{:.2f}", m.psnr) : "inf";
}

std::string biasText(const SweepResult& result, const ConfigurationOutcome& c) {
  return c.bias ? fmt::format("{:.4f}", result.references[c.reference].biases[*c.bias].gap()) : "";
}

uint64_t nonFinite(const ConfigurationOutcome& c) {
  return c.display.nonFiniteTest + c.hdr.nonFiniteTest;
}

std::string pathErrorText(const ConfigurationOutcome& c) {
  return c.pathErrors.empty() ? "" : fmt::format("{:.4f}", c.pathErrorMean());
}
std::string pathWorstText(const ConfigurationOutcome& c) {
  return c.pathErrors.empty() ? "" : fmt::format("{:.4f}", c.pathErrorWorst());
}

std::string pathTimesText(const SweepResult& result) {
  std::string times;
  for (double t : result.pathTimes) times += (times.empty() ? "" : ", ") + fmt::format("{:g}", t);
  return times + " s";
}

// One line per configuration along the camera path: the mean and worst LDR-FLIP over the path
// times and where the worst is.
std::vector<std::string> pathLines(const SweepResult& result) {
  std::vector<std::string> lines;
  if (result.pathTimes.empty()) return lines;
  lines.push_back(
      fmt::format("along the camera path, each configuration against its reference at {} path times "
                  "(camera.time = {}); the front judges the mean:",
                  result.pathTimes.size(), pathTimesText(result)));
  for (const auto& c : result.configurations) {
    if (c.pathErrors.empty()) continue;
    lines.push_back(fmt::format("{}: LDR-FLIP mean {:.4f}, worst {:.4f} at {:g} s", c.configuration.label,
                                c.pathErrorMean(), c.pathErrorWorst(), c.pathErrorWorstTime()));
  }
  return lines;
}

std::string frontSentence(const SweepResult& result) {
  std::string text;
  for (std::size_t i : frontByTime(result)) {
    const auto& c = result.configurations[i];
    text += fmt::format("{}{} ({:.3f} ms, FLIP {:.4f}{})", text.empty() ? "" : " → ", c.configuration.label,
                        c.frameGpu.median, sweepError(c), c.unresolved ? ", unresolved" : "");
  }
  return text;
}

}  // namespace

std::pair<uint32_t, uint32_t> renderedSize(const render::WorkloadConfig& workload, const RenderedImages& images) {
  // A merged sweep's images are its shards' thumbnails; its workloads hold the rendered size.
  if (workload.width && workload.height) return {workload.width, workload.height};
  return {images.display.width, images.display.height};
}

std::string sizeText(const render::WorkloadConfig& workload, const RenderedImages& images) {
  const auto [width, height] = renderedSize(workload, images);
  return fmt::format("{}x{}", width, height);
}

std::string errorColumnName(const SweepResult& result) {
  return result.lookKeys.empty() ? "LDR-FLIP" : "LDR-FLIP change from the scene's look";
}

double largestConvergenceGap(const SweepResult& result) {
  double gap = 0.0;
  for (const auto& r : result.references) gap = std::max(gap, r.convergenceGap());
  return gap;
}

std::vector<std::string> referenceLines(const SweepResult& result) {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < result.references.size(); ++i) {
    const ReferenceOutcome& r = result.references[i];
    std::string knobs;
    for (const auto& [k, v] : r.workload.knobs) knobs += " " + k + "=" + v;
    std::string line =
        fmt::format("reference {}: {} msaa={}{}; two renders {} (floor {:.5f})", i + 1, sizeText(r.workload, r.images),
                    r.workload.msaa, knobs, r.identical ? "bit-identical" : "differ",
                    r.repeatDisplay.flip ? r.repeatDisplay.flip->mean : 0.0);
    if (r.convergence) {
      line += fmt::format("; convergence gap {:.4f} (against {}): errors up to {:.4f} are unresolved",
                          r.convergenceGap(), r.convergence->label, kUnresolvedGapFactor * r.convergenceGap());
    }
    lines.push_back(line);
    for (const auto& b : r.biases) {
      lines.push_back(fmt::format("reference {}: bias of {} (its converged render against the reference): {:.4f}",
                                  i + 1, b.label, b.gap()));
    }
  }
  if (const std::vector<std::string> views = viewKeys(result); !views.empty()) {
    std::string keys;
    for (const auto& k : views) keys += (keys.empty() ? "" : ", ") + k;
    lines.push_back("varied content axis/axes " + keys +
                    ": each value is a different view with its own reference, so each view has its own front "
                    "and a configuration is only dominated by one of the same view");
  }
  if (!result.lookKeys.empty()) {
    std::string keys;
    for (const auto& k : result.lookKeys) keys += (keys.empty() ? "" : ", ") + k;
    lines.push_back("varied look knob(s) " + keys +
                    ": judged against the scene's own value, so their column is the change from the scene's look");
  }
  return lines;
}

std::vector<std::size_t> frontByTime(const SweepResult& result) {
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    if (result.configurations[i].onFront) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
    return result.configurations[a].frameGpu.median < result.configurations[b].frameGpu.median;
  });
  return front;
}

std::string pathMethodNote(const SweepResult& result) {
  if (result.pathTimes.empty()) return "";
  return fmt::format(
      " The scene flies a camera path: each configuration and each reference was also rendered alone at {} path "
      "times ({}: camera.time=T, the compared frame of a fresh workload), and the error the front judges is the "
      "mean of their LDR-FLIP means against the reference at the same time (the worst is reported beside it).",
      result.pathTimes.size(), pathTimesText(result));
}

std::string sweepMethodNote(const SweepResult& result) {
  std::string stop = result.untilStable
                         ? fmt::format(
                               "each configuration was sampled until the 95% interval of its median was within "
                               "±{:.1f}% of it (at least {} frames, at most {}, checked every {} frames)",
                               result.untilStable->relativeHalfWidth * 100.0, result.untilStable->minFrames,
                               result.frameCap, result.stableCheckFrames)
                         : fmt::format("each configuration was measured for {} frames", result.frameCap);
  return fmt::format(
      "Times are medians of the GPU frame time with a 95% distribution-free confidence interval (order statistics "
      "x(l), x(n+1-l) from the exact binomial distribution). Configurations were measured in {} interleaved rounds in "
      "a random order (seed {}), after {} warm-up frame(s), dropping {} re-warm frame(s) at the start of each visit; "
      "{}{}. Error is the LDR-FLIP mean of the tone-mapped frame against the reference (approximation knobs at "
      "their exact values, render.ssaa={}, the most MSAA the device has; look and content knobs as configured, a "
      "varied look knob at the scene's own value; cost-only knobs pinned); its "
      "noise floor ({:.5f}) is the LDR-FLIP mean between two renders of the reference, and its convergence gap "
      "(largest {:.5f}) the LDR-FLIP mean between it and the same reference one SSAA step down: an error within {}x "
      "that gap is unresolved, since the reference itself is not that converged. A configuration is dominated "
      "when another is significantly faster (one-sided Mann–Whitney U, α = {}) or equal in time, lower or equal in "
      "error beyond the floor, and strictly better in one; the front is the configurations no other dominates.",
      result.rounds, result.seed, result.warmupFrames, result.rewarmFrames, stop,
      result.stopReason == "time limit" ? " (stopped by --max-minutes)" : "", result.referenceRules.ssaa,
      result.errorFloor, largestConvergenceGap(result), kUnresolvedGapFactor, result.alpha);
}

nlohmann::json sweepJson(const SweepResult& result) {
  nlohmann::json axes = nlohmann::json::array();
  for (const auto& a : result.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  nlohmann::json references = nlohmann::json::array();
  for (const auto& r : result.references) references.push_back(referenceJson(r));
  nlohmann::json configurations = nlohmann::json::array();
  for (const auto& c : result.configurations) configurations.push_back(configurationJson(result, c));
  nlohmann::json front = nlohmann::json::array();
  for (std::size_t i : frontByTime(result)) front.push_back(result.configurations[i].configuration.label);
  const SweepOverhead& o = result.overhead;
  return {{"schema", kSweepSchema},
          {"tool_version", result.toolVersion},
          {"scene", result.scene},
          {"scene_hash", result.sceneHash},
          {"device",
           {{"name", result.device.name},
            {"driver", result.device.driver},
            {"type", result.device.type},
            {"api_version", result.device.apiVersion},
            {"host_timestamps", result.device.hostTimestamps}}},
          {"axes", axes},
          {"method", methodJson(result)},
          {"references", references},
          {"configurations", configurations},
          {"front", front},
          {"shard", shardJson(result)},
          {"merged_shards", result.mergedShards},
          {"wall_ms",
           {{"open", o.openMs},
            {"references", o.referenceMs},
            {"warmup", o.warmupMs},
            {"measure", o.measureMs},
            {"close", o.closeMs},
            {"metrics", o.metricsMs},
            {"report", o.reportMs},
            {"total", o.totalMs}}}};
}

std::string sweepCsv(const SweepResult& result) {
  std::string csv = "label";
  // (append ',' then the field: GCC 12's -Wrestrict misfires on "," + std::string here)
  for (const auto& a : result.axes) {
    csv += ',';
    csv += csvField(a.key);
  }
  csv +=
      ",width,height,msaa,frame_gpu_median_ms,ci_low_ms,ci_high_ms,frames,stable,ldr_flip_mean,hdr_flip_mean,"
      "rmse,psnr_db,hdr_rmse,nonfinite,front,unresolved,bias_ldr_flip_mean,dominated_by,path_ldr_flip_mean,"
      "path_ldr_flip_worst\n";
  for (const auto& c : result.configurations) {
    csv += csvField(c.configuration.label);
    for (const auto& [key, value] : c.configuration.point) {
      csv += ',';
      csv += csvField(value);
    }
    std::string dominatedBy;
    for (std::size_t d : c.dominatedBy)
      dominatedBy += (dominatedBy.empty() ? "" : ";") + result.configurations[d].configuration.label;
    csv += fmt::format(",{},{},{},{:.6f},{:.6f},{:.6f},{},{},{},{},{:.6f},{},{:.6f},{},{},{},{},{},{},{}\n",
                       renderedSize(c.configuration.workload, c.images).first,
                       renderedSize(c.configuration.workload, c.images).second, msaaUsed(c), c.frameGpu.median,
                       c.frameGpu.lower, c.frameGpu.upper, c.frameGpu.n, c.stable ? 1 : 0, flipText(c.display),
                       flipText(c.hdr), c.display.rmse, psnrText(c.display), c.hdr.rmse, nonFinite(c),
                       c.onFront ? 1 : 0, c.unresolved ? 1 : 0, biasText(result, c), csvField(dominatedBy),
                       pathErrorText(c), pathWorstText(c));
  }
  return csv;
}

std::string sweepTable(const SweepResult& result) {
  std::size_t width = 13;
  for (const auto& c : result.configurations) width = std::max(width, c.configuration.label.size());
  const bool look = !result.lookKeys.empty();
  std::string out;
  if (look) out += "  LDR-FLIP is the change from the scene's look (a look knob is varied)\n";
  out += fmt::format("  {:<{}}  {:>27}  {:>8}  {:>8}  {:>7}  {:>6}  {}\n", "configuration", width,
                     "GPU frame ms (95% CI)", look ? "Δlook" : "LDR-FLIP", "HDR-FLIP", "PSNR", "bias", "front");
  for (const auto& c : result.configurations) {
    const std::string time =
        fmt::format("{:.3f} [{:.3f}, {:.3f}]", c.frameGpu.median, c.frameGpu.lower, c.frameGpu.upper);
    std::string notes = c.onFront ? "front" : "";
    if (c.unresolved) notes += notes.empty() ? "unresolved" : ", unresolved";
    if (nonFinite(c)) notes += fmt::format("  {} NaN/Inf", nonFinite(c));
    out += fmt::format("{} {:<{}}  {:>27}  {:>8}  {:>8}  {:>7}  {:>6}  {}\n", c.onFront ? '*' : ' ',
                       c.configuration.label, width, time, flipText(c.display), flipText(c.hdr), psnrText(c.display),
                       c.bias ? biasText(result, c) : "-", notes);
  }
  out += "  front (fastest first): " + frontSentence(result) + "\n";
  out += fmt::format("  error floor (reference vs itself): {:.5f}; {} round(s), stop: {}\n", result.errorFloor,
                     result.rounds, result.stopReason);
  for (const std::string& line : referenceLines(result)) out += "  " + line + "\n";
  for (const std::string& line : pathLines(result)) out += "  " + line + "\n";
  return out;
}

std::string sweepMarkdown(const SweepResult& result) {
  std::string md =
      fmt::format("# Sweep: {}\n\nDevice: {} ({}). ", result.scene, result.device.name, result.device.driver);
  if (result.device.hostTimestamps) md += timestampSourceNote(result.device) + " ";
  md += "\n\n**Front (fastest first):** " + frontSentence(result) + "\n\n";
  md += fmt::format(
      "| | configuration | GPU frame ms | 95% CI | frames | {} | HDR-FLIP | RMSE | PSNR dB | NaN/Inf | bias | "
      "dominated by |\n"
      "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---|\n",
      errorColumnName(result));
  for (const auto& c : result.configurations) {
    std::string dominatedBy;
    for (std::size_t d : c.dominatedBy)
      dominatedBy += (dominatedBy.empty() ? "" : ", ") + result.configurations[d].configuration.label;
    md += fmt::format("| {} | {} | {:.4f} | [{:.4f}, {:.4f}] | {} | {}{} | {} | {:.5f} | {} | {} | {} | {} |\n",
                      c.onFront ? "**front**" : "", c.configuration.label, c.frameGpu.median, c.frameGpu.lower,
                      c.frameGpu.upper, c.frameGpu.n, flipText(c.display), c.unresolved ? " (unresolved)" : "",
                      flipText(c.hdr), c.display.rmse, psnrText(c.display), nonFinite(c),
                      c.bias ? biasText(result, c) : "-", dominatedBy);
  }
  if (!result.pathTimes.empty()) {
    md += fmt::format(
        "\n## Along the camera path\n\nEach configuration rendered alone at {} path times "
        "(`camera.time` = {}), each against its reference at the same time; the front judges the "
        "mean.\n\n| configuration | mean LDR-FLIP | worst | worst at s |",
        result.pathTimes.size(), pathTimesText(result));
    for (double t : result.pathTimes) md += fmt::format(" {:g} s |", t);
    md += "\n|---|---:|---:|---:|";
    for (std::size_t k = 0; k < result.pathTimes.size(); ++k) md += "---:|";
    md += "\n";
    for (const auto& c : result.configurations) {
      md += fmt::format("| {} | {} | {} | {:g} |", c.configuration.label, pathErrorText(c), pathWorstText(c),
                        c.pathErrorWorstTime());
      for (const PathTimeError& e : c.pathErrors) md += fmt::format(" {} |", flipText(e.display));
      md += "\n";
    }
  }
  md += "\n## References\n\n";
  for (const std::string& line : referenceLines(result)) md += "- " + line + "\n";
  md += "\n## Method\n\n" + sweepMethodNote(result) + pathMethodNote(result) + "\n";
  return md;
}

void writeSweepOutputs(const std::filesystem::path& dir, SweepResult& result) {
  Stopwatch timer;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw InputError(dir.string() + ": cannot create the output directory (" + ec.message() + ")");
  }
  if (result.shard) writeShardImages(dir, result);
  writeFileAtomic(dir / "sweep.csv", sweepCsv(result));
  writeFileAtomic(dir / "sweep.md", sweepMarkdown(result));
  writeFileAtomic(dir / "sweep.html", sweepHtml(result));
  // Last, so that it holds the report phase (all but its own writing).
  result.overhead.reportMs = timer.elapsedMs();
  writeFileAtomic(dir / "sweep.json", dumpJson(sweepJson(result)));
  result.overhead.reportMs = timer.elapsedMs();
}

std::string sweepWallSummary(const SweepResult& result) {
  const SweepOverhead& o = result.overhead;
  const auto s = [](double ms) { return fmt::format("{:.1f} s", ms / 1000.0); };
  uint32_t renders = 0;
  for (const auto& r : result.references)
    renders += static_cast<uint32_t>(r.renders.size() + r.biases.size() + (r.convergence ? 1 : 0));
  std::string text = fmt::format(
      "sweep: wall {}: open {}, references {} ({} render(s)), warm-up {}, measuring {}, closing {}, metrics {}, "
      "report {}\n",
      s(o.totalMs + o.reportMs), s(o.openMs), s(o.referenceMs), renders, s(o.warmupMs), s(o.measureMs), s(o.closeMs),
      s(o.metricsMs), s(o.reportMs));
  for (std::size_t i = 0; i < result.references.size(); ++i) {
    const auto& r = result.references[i];
    text += fmt::format("sweep:   reference {} ({}):", i + 1, sizeText(r.workload, r.images));
    for (const auto& w : r.renders) {
      text += fmt::format(" [open {}, frames {}, readback {}]", s(w.openMs), s(w.framesMs), s(w.readbackMs));
    }
    if (r.convergence) {
      const ReferenceRenderWall& w = r.convergence->wall;
      text += fmt::format(" convergence {} [open {}, frames {}, readback {}]", r.convergence->label, s(w.openMs),
                          s(w.framesMs), s(w.readbackMs));
    }
    for (const auto& b : r.biases)
      text += fmt::format(" bias {} [open {}, frames {}]", b.label, s(b.wall.openMs), s(b.wall.framesMs));
    text += "\n";
  }
  for (const auto& c : result.configurations) {
    const std::size_t measured = c.run.frameGpuMs.size();
    const uint32_t rendered = static_cast<uint32_t>(measured) + c.wall.rewarmFrames;
    text += fmt::format(
        "sweep:   {}: open {}, warm-up {} ({} frames), measuring {} ({} measured + {} re-warm frames in {} visit(s), "
        "{:.2f} s a frame), metrics {}\n",
        c.configuration.label, s(c.wall.openMs), s(c.wall.warmupMs), c.wall.warmupFrames, s(c.wall.measureMs), measured,
        c.wall.rewarmFrames, c.wall.visits, rendered ? c.wall.measureMs / 1000.0 / rendered : 0.0, s(c.wall.metricsMs));
  }
  return text;
}

}  // namespace fgb::harness
