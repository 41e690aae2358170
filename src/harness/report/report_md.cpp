#include <fgb/harness/report/report.hpp>

#include <fmt/format.h>

#include <cmath>

namespace fgb::harness {
namespace {

std::string budgetCell(const RunResult& run, const std::string& pass) {
  if (!run.budget) return "–";
  for (const auto& line : run.budget->lines) {
    if (line.pass != pass) continue;
    if (line.status == "missing") return fmt::format("{:.3f} (not measured)", line.budgetMs);
    if (line.status == "over") return fmt::format("{:.3f} **over by {:+.3f} ms ({:+.0f}%)**", line.budgetMs, line.overMs(), line.overPercent());
    if (line.summedPasses > 0) return fmt::format("{:.3f} ok (sum of {} passes)", line.budgetMs, line.summedPasses);
    return fmt::format("{:.3f} ok", line.budgetMs);
  }
  return "–";
}

std::string summaryCells(const Summary& s) {
  return fmt::format("{:.4f} | {:.4f} | {:.4f} | {:.4f} | {:.4f} | {:.4f} | {}", s.median, s.p5, s.p95, s.mean, s.min, s.max, s.n);
}

std::string passTable(const RunResult& run) {
  std::string out = "| pass | queue | median | p5 | p95 | mean | min | max | n | budget | stable |\n"
                    "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|\n";
  for (const auto& p : run.passes) {
    if (p.culled) {
      out += fmt::format("| {} | {} | culled | | | | | | 0 | {} | |\n", p.name, p.queue, budgetCell(run, p.name));
      continue;
    }
    out += fmt::format("| {} | {} | {} | {} | {} |\n", p.name, p.queue, summaryCells(p.gpu), budgetCell(run, p.name),
                       p.unstable ? "**unstable**" : "yes");
  }
  out += fmt::format("| **frame (GPU)** | | {} | {} | |\n", summaryCells(run.frameGpu), budgetCell(run, "(frame)"));
  out += fmt::format("| **frame (CPU)** | | {} | – | |\n", summaryCells(run.frameCpu));
  return out;
}

// The calibration: each pass's span beside its isolated cost and its critical-path share.
std::string isolatedSection(const RunResult& run) {
  if (run.isolatedFrames == 0) return "";
  std::string out = "## Span, isolated cost and critical path\n\n" + isolatedCostNote(run) +
                    "\n\n| pass | span | isolated | critical path |\n|---|---:|---:|---:|\n";
  for (const auto& p : run.passes) {
    if (p.culled || !p.hasIsolated()) continue;
    out += fmt::format("| {} | {:.4f} | {:.4f} | {} |\n", p.name, p.gpu.median, p.isolated.median,
                       p.criticalShare >= 0.0 ? fmt::format("{:.1f}%", 100.0 * p.criticalShare) : "–");
  }
  return out + "\n";
}

// --check-finite: the first pass that wrote a bad value, and every checked pass's counts.
// Along a camera path: the frame-time distribution and the slowest frames, each with the knob that
// renders it alone.
std::string pathSection(const RunResult& run) {
  const auto slowest = run.slowestFrames(3);
  if (slowest.empty()) return "";
  std::string out = fmt::format(
      "## Camera path\n\n{} measured frames from {:g} s to {:g} s of the path. GPU frame: median {:.4f} ms, p95 {:.4f}, "
      "p99 {:.4f}, worst {:.4f}; CPU frame: median {:.4f} ms, p95 {:.4f}, p99 {:.4f}, worst {:.4f}.\n\n",
      run.framePathTimeS.size(), run.framePathTimeS.front(), run.framePathTimeS.back(), run.frameGpu.median,
      run.frameGpu.p95, run.frameGpu.p99, run.frameGpu.max, run.frameCpu.median, run.frameCpu.p95, run.frameCpu.p99,
      run.frameCpu.max);
  out += "### Slowest frames along the camera path\n\n| frame | path time (s) | GPU ms | CPU ms | render it alone |\n|---:|---:|---:|---:|---|\n";
  for (const std::size_t f : slowest) {
    out += fmt::format("| {} | {:g} | {:.4f} | {:.4f} | `--set camera.time={}` |\n", f, run.framePathTimeS[f],
                       run.frameGpuMs[f], f < run.frameCpuMs.size() ? run.frameCpuMs[f] : 0.0, run.framePathTimeS[f]);
  }
  return out + "\n";
}

std::string finiteSection(const RunResult& run) {
  if (!run.checkedFinite) return "";
  std::string out = "## Non-finite values (`--check-finite`, last frame)\n\n";
  const auto* first = run.firstNonFinite();
  out += first ? fmt::format("First bad value produced by **{}** (NaN {}, Inf {}, above half of R16F max {} pixels).\n\n",
                             first->pass, first->nan, first->inf, first->overHalfMax)
               : fmt::format("None: {} checked passes wrote only finite values within half of R16F's maximum.\n\n",
                             run.nonFinite.size());
  out += "| pass (execution order) | NaN | Inf | > 32752 |\n|---|---:|---:|---:|\n";
  for (const auto& c : run.nonFinite) out += fmt::format("| {} | {} | {} | {} |\n", c.pass, c.nan, c.inf, c.overHalfMax);
  return out + "\n";
}

std::string budgetSection(const RunResult& run) {
  if (!run.budget) return "## Budget\n\nNo budget given (`--budget FILE`).\n";
  const auto& b = *run.budget;
  std::string out = fmt::format("## Budget: {}\n\nVerdict: **{}** (tolerance {:.0f}%; {}).\n\n", b.file, b.verdict,
                                b.tolerance * 100.0, b.judgedOn());
  for (const auto* line : b.failing()) {
    if (line->status == "missing") {
      out += fmt::format("- {}: budget {:.3f} ms, not measured (pass absent or culled)\n", line->pass, line->budgetMs);
    } else {
      out += fmt::format("- {}: {:.4f} ms against {:.3f} ms, over by {:.4f} ms ({:+.1f}%){}\n", line->pass, *line->measuredMs,
                         line->budgetMs, line->overMs(), line->overPercent(),
                         line->summedPasses ? fmt::format(" (sum of {} passes)", line->summedPasses) : "");
    }
  }
  for (const auto& w : b.warnings) out += "- note: " + w + "\n";
  return out;
}

std::string goldenSection(const RunResult& run) {
  if (!run.golden) return "## Golden image\n\nNo golden compared (`--golden PATH`).\n";
  const auto& g = *run.golden;
  std::string out = fmt::format("## Golden image: {}\n\nVerdict: **{}**.\n\n", g.file, g.verdict);
  out += "| image | max abs | RMSE | PSNR dB | share over | FLIP mean | FLIP p99 | NaN/Inf | failures |\n"
         "|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& image : g.images) {
    const auto& m = image.metrics;
    std::string failures;
    for (const auto& f : image.failures) failures += (failures.empty() ? "" : "; ") + f;
    out += fmt::format("| {} | {:.5f} | {:.5f} | {} | {:.4f} | {} | {} | {} | {} |\n", image.kind, m.maxAbsError, m.rmse,
                       std::isfinite(m.psnr) ? fmt::format("{:.2f}", m.psnr) : "∞", m.shareOverThreshold,
                       m.flip ? fmt::format("{:.5f}", m.flip->mean) : "–", m.flip ? fmt::format("{:.5f}", m.flip->p99) : "–",
                       m.nonFiniteReference + m.nonFiniteTest, failures.empty() ? "none" : failures);
  }
  if (!g.diffImage.empty()) out += "\nDiff heat map: `" + g.diffImage + "`\n";
  if (!run.firstDifference.empty()) out += "\nPer-pass goldens: " + run.firstDifference + "\n";
  return out;
}

}  // namespace

std::string msaaLabel(uint32_t msaa) { return msaa ? std::to_string(msaa) : std::string("scene default"); }

std::string timestampSourceNote(const render::DeviceDescription& device) {
  if (device.hostTimestamps) {
    return "GPU timestamps on this device come from the host clock (" + device.name +
           " is a CPU implementation): pass times measure CPU work, not a GPU.";
  }
  return fmt::format("GPU timestamps from the device (period {} ns).", device.timestampPeriodNs);
}

std::string hostOverheadNote(const RunResult& run) {
  const HarnessOverhead& o = run.overhead;
  const render::StartupTimes& s = o.startup;
  return fmt::format(
      "Host time apart from GPU time: start-up {:.1f} ms (scene {:.1f}, device {:.1f}, upload {:.1f}, features and "
      "graph {:.1f} of which {} pipelines {:.1f} with the on-disk pipeline cache {}); harness overhead in the "
      "measured loop {:.3f} ms ({:.1f} µs per frame, apart from {:.3f} ms inside the workload); readback {:.1f} ms; "
      "EXR + PNG encoding {:.1f} ms.",
      o.openMs, s.sceneMs, s.deviceMs, s.uploadMs, s.graphMs, s.pipelines, s.pipelinesMs, s.pipelineCache, o.harnessMs,
      o.perFrameUs, o.workloadCallsMs, o.readbackMs, o.encodeMs);
}

std::string isolatedCostNote(const RunResult& run) {
  return fmt::format(
      "Span: the pass's first to last timestamp in the measured frames (queues overlap there). Isolated: the pass "
      "alone on an idle device ({} calibration frames, medians). Critical path: how much shorter the frame's longest "
      "chain through the compiled schedule (data, queue order, semaphore waits; isolated costs) would be without "
      "the pass.",
      run.isolatedFrames);
}

std::string wallClockNote(const RunResult& run) {
  return "Timer against the clock: the frame's span is its first to its last GPU timestamp; the wall time per "
         "frame is the measured frames' wall time, submitted back to back with one wait at the end. " +
         describeWallClock(run.wallClock) + ". " + describeDeviceState(run.deviceState) + ".";
}

std::string asyncComputeNote(const RunResult& run) {
  const AsyncComparison& async = run.asyncCompute;
  if (!async.compared()) return "";
  std::string note = "Async compute: " + describeAsync(async) + ".";
  double isolatedSum = 0.0;
  for (const auto& pass : run.passes) isolatedSum += pass.hasIsolated() ? pass.isolated.median : 0.0;
  const double gaps = summarize(async.idleGapsMs).median;
  const double busy = async.singleQueueFrame.median - gaps;
  if (isolatedSum > 0.0 && busy > 0.0) {
    note += fmt::format(
        " On one queue the frame idles {:.4f} ms between passes (barriers, submits, waits); the isolated costs add "
        "up to {:.4f} ms, {:+.1f}% of the one-queue frame without those gaps.",
        gaps, isolatedSum, 100.0 * (isolatedSum / busy - 1.0));
  }
  return note;
}

std::string markdownReport(const RunResult& run) {
  std::string out = fmt::format("# fgbench report: {}\n\n", run.scene);
  out += fmt::format("- Device: {} ({}), driver {}, Vulkan {}\n", run.device.name, run.device.type, run.device.driver,
                     run.device.apiVersion);
  out += "- Timestamps: " + timestampSourceNote(run.device) + "\n";
  out += fmt::format("- Config: {}x{}, MSAA {}, {} measured frames after {} warm-up\n", run.config.width, run.config.height,
                     msaaLabel(run.config.msaa), run.config.frames, run.config.warmup);
  for (const auto& [k, v] : run.config.knobs) out += fmt::format("- Knob: {} = {}\n", k, v);
  out += fmt::format("- Tool version {}, scene hash {}\n\n", run.toolVersion, run.sceneHash.empty() ? "–" : run.sceneHash);
  if (!run.stats.empty()) {
    out += "## Scene\n\n| statistic | value |\n|---|---:|\n";
    for (const auto& [k, v] : run.stats) out += fmt::format("| {} | {:g} |\n", k, v);
    out += "\n";
  }
  out += "## Timings (ms)\n\n" + passTable(run) + "\n";
  out += isolatedSection(run);
  out += fmt::format("Unstable: (p95 − p5) / median > {:.0f}%.\n\n", kDefaultUnstableSpread * 100.0);
  out += hostOverheadNote(run) + "\n\n";
  out += wallClockNote(run) + "\n\n";
  if (const std::string async = asyncComputeNote(run); !async.empty()) out += async + "\n\n";
  out += pathSection(run);
  out += finiteSection(run);
  out += budgetSection(run) + "\n" + goldenSection(run);
  return out;
}

}  // namespace fgb::harness
