// A sweep's outputs: sweep.json (schema in docs/sweep.md), sweep.csv, sweep.md, a single-file
// sweep.html with inline SVG charts and inline images, and the terminal table.
#pragma once

#include <fgb/harness/sweep/sweep.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace fgb::harness {

nlohmann::json sweepJson(const SweepResult& result);
std::string sweepCsv(const SweepResult& result);
std::string sweepMarkdown(const SweepResult& result);
std::string sweepTable(const SweepResult& result);  // the terminal's table, front marked with '*'
std::string sweepHtml(const SweepResult& result);

// The HTML's charts, each a standalone <svg> (exposed for tests).
std::string timeErrorSvg(const SweepResult& result);  // log-log, error bars on both axes, front drawn
std::string passStackSvg(const SweepResult& result);  // per-pass median times stacked per configuration

// The front's configurations, fastest first (indices into result.configurations).
std::vector<std::size_t> frontByTime(const SweepResult& result);
// The size a configuration or reference rendered at (WxH): its workload's, else its images'.
std::pair<uint32_t, uint32_t> renderedSize(const render::WorkloadConfig& workload, const RenderedImages& images);
std::string sizeText(const render::WorkloadConfig& workload, const RenderedImages& images);
// How the sweep measured and decided, in one paragraph (reports and --help say the same).
std::string sweepMethodNote(const SweepResult& result);
// Along a camera path, what the method note adds: where the error was judged (empty when still).
std::string pathMethodNote(const SweepResult& result);

// The error column's name: "LDR-FLIP", or "LDR-FLIP change from the scene's look" where the sweep
// varies a look knob (bloom.mips, post.*), whose reference keeps the scene's own value.
std::string errorColumnName(const SweepResult& result);
// The largest convergence gap of the sweep's references (0 when none was checked).
double largestConvergenceGap(const SweepResult& result);
// The references in words: how each was made, its convergence gap, the unresolved band and each
// cost-only value's bias, one line each.
std::vector<std::string> referenceLines(const SweepResult& result);

// Creates DIR if needed (InputError when impossible) and writes sweep.csv, sweep.md, sweep.html and
// sweep.json, each atomically; fills result.overhead.reportMs (sweep.json, written last, holds the
// time of writing the others).
void writeSweepOutputs(const std::filesystem::path& dir, SweepResult& result);

// Where the sweep's wall time went, for stderr: the phases, each reference render, and per
// configuration its opening, warm-up, measuring visits and metrics.
std::string sweepWallSummary(const SweepResult& result);

}  // namespace fgb::harness
