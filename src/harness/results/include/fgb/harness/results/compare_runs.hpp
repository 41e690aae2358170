// Run-to-run regression test between two sets of benchmark runs (timings.json files). The frames of
// one run are not independent samples of a build: a run-level shift (machine load, caches, clocks,
// scheduling) moves every frame of a run alike and dwarfs the noise between frames, so a test on
// pooled frames calls such shifts "significant" (issue 27). The unit of replication is the run:
//
// - each run is reduced to one number per pass, its median over frames;
// - each side's runs are averaged on a log scale (a geometric mean: changes are relative);
// - the run-to-run noise is the larger of the noise the runs show (pooled standard deviation of
//   the log medians) and the device class's noise model (runNoiseModel(): measured, per class), so
//   a few runs that happen to agree closely cannot claim a change the device's noise explains;
// - a one-sided test of the mean log difference (Welch/Student t when the runs' own spread decides,
//   normal when the model does) at `alpha`, plus a minimum effect (relative and absolute), gives
//   three verdicts, as Chromium's Pinpoint does: a change ("slower"/"faster"), "same" (too small
//   to matter, or with one run a side inside the frame-to-frame noise), or "unknown" (big enough to
//   matter but not significant with these runs: add runs).
#pragma once

#include <fgb/harness/results/timings.hpp>
#include <fgb/harness/stats/mann_whitney.hpp>
#include <fgb/harness/stats/stats.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace fgb::harness {

// Run-to-run noise of a device class: one standard deviation of a pass's run median between
// separate runs of the same binary and configuration, relative to the median:
// sqrt(relative^2 + (absoluteMs / medianMs)^2) (short passes add a constant jitter).
struct RunNoise {
  std::string deviceClass;  // "cpu" | "discrete" | "integrated"
  double relative = 0.0;
  double absoluteMs = 0.0;
  std::string measured;  // how the numbers were measured, one phrase

  [[nodiscard]] double sigma(double medianMs) const;
};

// The table (compare_runs.cpp): one entry per device class.
const std::vector<RunNoise>& runNoiseModel();
// The model for a timings.json device.type ("cpu", "discrete", "integrated", ...). Types the table
// lacks ("virtual", "other", unknown) get the noisiest class's entry.
const RunNoise& runNoiseFor(const std::string& deviceType);

struct CompareRunsOptions {
  double alpha = 0.01;      // one-sided significance level, per pass
  double minEffect = 0.05;  // relative change of the median that matters (5%)
  double minAbsMs = 0.01;   // and in absolute terms: smaller shifts are timer and scheduling noise
  double power = 0.8;       // of the "detectable" column: the change found with this probability
  std::string deviceClass;  // noise model to use; empty: the runs' device.type
  double runNoise = -1.0;   // >= 0: the model's relative term instead of the table's (a measured machine)
};

// Fewer runs a side than this and the verdicts lean on the device class's noise model (LLVM LNT
// asks for 4 samples a side).
inline constexpr std::size_t kRecommendedRuns = 4;

struct PassComparison {
  std::string pass;  // "(frame)" for the whole frame
  // Each side: the per-run medians (ms), their geometric mean (= the median with one run) and the
  // frames behind them. The Summary of one run is the frames' (added / removed rows).
  Summary before, after;
  std::vector<double> beforeRuns, afterRuns;
  std::size_t beforeFrames = 0, afterFrames = 0;
  double deltaMs = 0.0;
  double deltaRelative = 0.0;  // after.median / before.median - 1
  double noise = 0.0;          // run-to-run relative standard deviation used
  bool noiseFromRuns = false;  // the runs' own spread (else the device class's model)
  double band = 0.0;           // smallest relative change significant with these runs
  double detectable = 0.0;     // smallest change found with probability `power` (>= minEffect)
  double pSlower = 1.0, pFaster = 1.0;  // the run-level test
  // Mann–Whitney U on the run medians (both sides >= 2 runs), else on the frames of the two runs
  // (the frame-noise check of a single run a side).
  MannWhitneyResult test;
  bool testOnRuns = false;
  // "slower" | "faster" | "same" | "unknown" | "added" | "removed" | "culled"
  std::string verdict;
};

// Camera paths: the GPU frame time frame by frame, where every run of both sides flew the same
// path times (each frame's geometric mean over a side's runs). Informational: the verdict stays
// the medians' (frames of one run share its load).
struct PathFrameComparison {
  std::size_t frame = 0;
  double pathTimeS = 0.0;
  double beforeMs = 0.0, afterMs = 0.0;
  [[nodiscard]] double ratio() const { return beforeMs > 0.0 ? afterMs / beforeMs : 0.0; }
};

struct RunsComparison {
  std::vector<PassComparison> rows;
  std::vector<PathFrameComparison> pathFrames;  // empty unless both sides flew the same path times
  CompareRunsOptions options;
  RunNoise model;
  std::size_t beforeRuns = 0, afterRuns = 0;
  // What the pass rows judge: "isolated" costs where every run has them, else "span"s (the
  // frame row always judges the frame's span).
  std::string passCost = "span";
  std::vector<std::string> warnings;
  [[nodiscard]] bool anySlower() const;
  [[nodiscard]] bool anyUnknown() const;
  // "slower" if any pass is, else "unknown" if any is, else "same".
  [[nodiscard]] std::string verdict() const;
};

// One run a side (the contract of `compare-runs OLD NEW`).
RunsComparison compareRuns(const LoadedTimings& before, const LoadedTimings& after, const CompareRunsOptions& options = {});
// Several runs a side (each a separate process, ideally interleaved A B A B ...).
RunsComparison compareRuns(const std::vector<LoadedTimings>& before, const std::vector<LoadedTimings>& after,
                           const CompareRunsOptions& options = {});

// The timings.json files a path names: the file itself; a run's output directory (holding
// timings.json); or a directory of such run directories and/or *.json files, in natural order
// (r2 before r10). InputError when it names none.
std::vector<std::filesystem::path> timingsFilesIn(const std::filesystem::path& path);

std::string formatTable(const RunsComparison& comparison);
nlohmann::json toJson(const RunsComparison& comparison);

// Student t distribution with `df` > 0 degrees of freedom: P(T <= t), and its quantile.
double studentTCdf(double t, double df);
double studentTQuantile(double p, double df);
// Standard normal quantile.
double normalQuantile(double p);

// What one run's frames can detect: the smallest relative change of the median that a one-sided
// test at `alpha` finds with probability `power` between two runs of this many frames with this
// frame-to-frame noise, (z(1 - alpha) + z(power)) * sqrt(2) * se, the median's standard error se
// taken from its 95% interval (half-width / 1.96). Frames of one run share its load, so between
// builds compare-runs' run-to-run noise applies on top: this is the floor, not the promise.
// +inf when the interval is not usable (too few frames, a zero median).
inline constexpr double kDetectAlpha = 0.05, kDetectPower = 0.8;
double detectableFromFrames(const std::vector<double>& samples);
// The median's relative 95% half-width at which detectableFromFrames gives `detectable`
// (`--detect` for `--until-stable`).
double halfWidthForDetectable(double detectable);

}  // namespace fgb::harness
