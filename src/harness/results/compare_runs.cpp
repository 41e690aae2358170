#include <fgb/harness/results/compare_runs.hpp>

#include <fgb/core/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fgb::harness {

// Run-to-run noise per device class: one standard deviation of a pass's per-run median between
// separate `fgbench run` processes of the same binary and configuration, relative (log scale),
// plus an absolute jitter that dominates short passes. A change smaller than what this noise
// explains is not claimed, however closely a few runs agree; `--run-noise` replaces the relative
// term for a machine whose own noise was measured.
//
// cpu: lavapipe (llvmpipe 25.0.7, LLVM 15, 256-bit) on the 2-core build machine shared with two
//   other engineers' builds and tests (load average 4-6), issue 27's configuration: atrium.json
//   --width 320 --height 180 --frames 32 --set render.path=visbuffer, 20 separate runs (rounds 1-10
//   of `bench/ab-runs.sh -r 20`, same binary both sides). Standard deviation of log(run median):
//   the heavy multi-threaded passes 29-33% (Triangle Filter 31.5%, Material Shade 30.4%, Visibility
//   Raster 32.8%, Mesh Render Transparent 30.6%, Bloom 28.8%, frame 31.5%; medians 3.5-190 ms),
//   light ones 6-21% (Clustered Light Cull 13.1%, Cluster Cull 21.1%, Mesh Frustum Cull 5.9%);
//   `relative` is the 75th percentile over passes with a median >= 0.05 ms. Passes of 5-20 us vary
//   by 9-21%, about 2 us: `absoluteMs`. 20 more runs one after another, at a lower load average
//   (~3.5), varied by 21-24% (heavy passes). A quiet machine varies less: measure it, --run-noise.
//   With this table, none of 30 A/A pairs of single runs was called slower (per-frame test: 15).
// discrete: measured on an NVIDIA H200 (driver 580.159.04), atrium 1920x1080, 64 frames a run,
//   bench/ab-runs.sh -r 20 (forward) and -r 8 (visbuffer), A/A pairs of single runs: per pass the
//   A/A difference of medians had a standard deviation of at most 0.53 us (max |delta| 1.04 us;
//   Mesh Render 1.8 us at 14.4 ms), at most 0.3% for passes >= 0.05 ms, frame 0.02-0.12%. The
//   relative term keeps LLVM LNT's 1% floor (< 1% is not a change, and other GPUs and machines vary
//   more); the absolute term is 1 us, twice the largest per-pass spread measured. With it,
//   visbuffer: 0 of 20 A/A pairs called slower, a 10% debug.slow_pass on Material Shade (0.17 ms;
//   +10.9% measured) named slower in 20 of 20 pairs and no other pass; forward (judged with the
//   first model, 1% + 10 us, the same sigma for Mesh Render): 0 of 20 and 20 of 20 (+9.8%).
// integrated: not measured yet: between the two (shared memory and clocks with the CPU; thermal
//   throttling), 3% until someone measures one with bench/ab-runs.sh.
const std::vector<RunNoise>& runNoiseModel() {
  static const std::vector<RunNoise> table = {
      {"cpu", 0.30, 0.002,
       "lavapipe on a loaded 2-core machine: atrium visbuffer 320x180 x32 frames, 20 separate runs"},
      {"discrete", 0.01, 0.001,
       "H200: per-pass A/A spread <= 0.53 us and <= 0.3% (atrium 1080p, 28 pairs); LNT's 1% floor per pass"},
      {"integrated", 0.03, 0.01, "not measured: between cpu and discrete until measured"},
  };
  return table;
}

const RunNoise& runNoiseFor(const std::string& deviceType) {
  const auto& table = runNoiseModel();
  for (const auto& entry : table)
    if (entry.deviceClass == deviceType) return entry;
  return *std::max_element(table.begin(), table.end(),
                           [](const RunNoise& a, const RunNoise& b) { return a.relative < b.relative; });
}

double RunNoise::sigma(double medianMs) const {
  const double jitter = medianMs > 0.0 ? absoluteMs / medianMs : 0.0;
  return std::sqrt(relative * relative + jitter * jitter);
}

// --- distributions ---

namespace {

// Continued fraction of the regularized incomplete beta function (modified Lentz).
double betaContinuedFraction(double a, double b, double x) {
  constexpr double tiny = 1e-300;
  double c = 1.0;
  double d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 300; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < 1e-15) break;
  }
  return h;
}

double incompleteBeta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front =
      std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * betaContinuedFraction(a, b, x) / a;
  return 1.0 - front * betaContinuedFraction(b, a, 1.0 - x) / b;
}

// Inverse of a continuous increasing cdf by bisection (cdf(lo) < p < cdf(hi)).
template <class Cdf>
double invert(Cdf cdf, double p, double lo, double hi) {
  for (int i = 0; i < 200 && hi - lo > 1e-12 * std::max(1.0, std::abs(lo)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double studentTCdf(double t, double df) {
  const double tail = 0.5 * incompleteBeta(df / 2.0, 0.5, df / (df + t * t));
  return t >= 0.0 ? 1.0 - tail : tail;
}

double studentTQuantile(double p, double df) {
  return invert([df](double t) { return studentTCdf(t, df); }, p, -1e6, 1e6);
}

double normalQuantile(double p) { return invert(normalCdf, p, -40.0, 40.0); }

namespace {
// detectable = this factor * the median's relative 95% half-width.
double detectPerHalfWidth() {
  return (normalQuantile(1.0 - kDetectAlpha) + normalQuantile(kDetectPower)) * std::sqrt(2.0) / normalQuantile(0.975);
}
}  // namespace

double detectableFromFrames(const std::vector<double>& samples) {
  return detectPerHalfWidth() * medianConfidenceInterval(samples).relativeHalfWidth();
}

double halfWidthForDetectable(double detectable) {
  return detectable / detectPerHalfWidth();
}

// --- the comparison ---

namespace {

const PassRecord* find(const LoadedTimings& t, const std::string& name) {
  for (const auto& p : t.passes) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return percentileOfSorted(values, 50.0);
}

double meanOf(const std::vector<double>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

// The samples of one pass in every run of a side (empty vectors: the pass is culled or missing).
struct Side {
  std::vector<std::vector<double>> frames;  // per run
  std::vector<double> runMedians;
  std::size_t frameCount = 0;
  bool missing = false;  // some run lacks the pass
  bool culled = false;   // some run has it culled or without samples
};

template <class Samples>
Side sideOf(const std::vector<LoadedTimings>& runs, Samples samplesOf) {
  Side side;
  for (const auto& run : runs) {
    const std::vector<double>* samples = samplesOf(run, side);
    if (samples == nullptr) continue;
    if (samples->empty()) {
      side.culled = true;
      continue;
    }
    side.frames.push_back(*samples);
    side.runMedians.push_back(median(*samples));
    side.frameCount += samples->size();
  }
  return side;
}

// Isolated costs are judged only where every run has them (a run of --no-isolate, or a
// timings.json from before the calibration, has spans alone).
bool everyRunIsolated(const std::vector<LoadedTimings>& runs) {
  return std::all_of(runs.begin(), runs.end(), [](const LoadedTimings& run) {
    return std::any_of(run.passes.begin(), run.passes.end(), [](const PassRecord& p) { return p.hasIsolated(); });
  });
}

Side passSide(const std::vector<LoadedTimings>& runs, const std::string& pass, bool isolated) {
  return sideOf(runs, [&](const LoadedTimings& run, Side& side) -> const std::vector<double>* {
    const PassRecord* p = find(run, pass);
    if (p == nullptr) {
      side.missing = true;
      return nullptr;
    }
    if (p->culled) {
      side.culled = true;
      return nullptr;
    }
    return isolated ? &p->isolatedMs : &p->samplesMs;
  });
}

Side frameSide(const std::vector<LoadedTimings>& runs) {
  return sideOf(runs, [](const LoadedTimings& run, Side&) { return &run.frameGpuMs; });
}

std::string judge(const PassComparison& row, const CompareRunsOptions& o, bool singleRuns) {
  const bool bigEnough = std::abs(row.deltaRelative) >= o.minEffect && std::abs(row.deltaMs) >= o.minAbsMs;
  if (!bigEnough) return "same";
  if (row.deltaMs > 0 && row.pSlower < o.alpha) return "slower";
  if (row.deltaMs < 0 && row.pFaster < o.alpha) return "faster";
  // A change that would matter, inside the run-to-run noise. With one run a side, a difference the
  // frames of the two runs do not even show (within the frame-to-frame noise) is no change.
  if (singleRuns && row.test.pAGreater >= o.alpha && row.test.pALess >= o.alpha) return "same";
  return "unknown";
}

PassComparison compareSides(std::string name, const Side& before, const Side& after, const RunNoise& model,
                            const CompareRunsOptions& o) {
  PassComparison row;
  row.pass = std::move(name);
  row.beforeRuns = before.runMedians;
  row.afterRuns = after.runMedians;
  row.beforeFrames = before.frameCount;
  row.afterFrames = after.frameCount;
  const double ka = static_cast<double>(before.runMedians.size());
  const double kb = static_cast<double>(after.runMedians.size());

  // Log medians; a zero median (a pass that did nothing measurable) is floored at 1 ns.
  const auto logs = [](const std::vector<double>& medians) {
    std::vector<double> out;
    for (const double m : medians) out.push_back(std::log(std::max(m, 1e-6)));
    return out;
  };
  const std::vector<double> la = logs(before.runMedians);
  const std::vector<double> lb = logs(after.runMedians);
  const double meanA = meanOf(la), meanB = meanOf(lb);
  std::vector<double> pooledFrames;
  for (const auto& run : before.frames) pooledFrames.insert(pooledFrames.end(), run.begin(), run.end());
  row.before = summarize(pooledFrames);
  pooledFrames.clear();
  for (const auto& run : after.frames) pooledFrames.insert(pooledFrames.end(), run.begin(), run.end());
  row.after = summarize(pooledFrames);
  // The level of a side: the geometric mean of its run medians (one run: its median).
  row.before.median = std::exp(meanA);
  row.after.median = std::exp(meanB);
  row.deltaMs = row.after.median - row.before.median;
  row.deltaRelative = row.before.median > 0 ? row.after.median / row.before.median - 1.0 : 0.0;

  // Run-to-run noise: the runs' own (pooled over both sides) when they show more than the model.
  double squares = 0.0;
  for (const double v : la) squares += (v - meanA) * (v - meanA);
  for (const double v : lb) squares += (v - meanB) * (v - meanB);
  const double df = ka + kb - 2.0;
  const double observed = df > 0 ? std::sqrt(squares / df) : 0.0;
  const double modelled = model.sigma(row.before.median);
  row.noiseFromRuns = observed > modelled;
  row.noise = std::max(observed, modelled);
  const double se = row.noise * std::sqrt(1.0 / ka + 1.0 / kb);
  const auto quantile = [&](double p) { return row.noiseFromRuns ? studentTQuantile(p, df) : normalQuantile(p); };
  const double critical = quantile(1.0 - o.alpha);
  const double statistic = se > 0 ? (meanB - meanA) / se : 0.0;
  const double cdf = row.noiseFromRuns ? studentTCdf(statistic, df) : normalCdf(statistic);
  row.pSlower = 1.0 - cdf;
  row.pFaster = cdf;
  row.band = std::expm1(critical * se);
  row.detectable = std::max({o.minEffect, std::expm1((critical + quantile(o.power)) * se),
                             row.before.median > 0 ? o.minAbsMs / row.before.median : 0.0});

  const bool singleRuns = before.runMedians.size() == 1 && after.runMedians.size() == 1;
  row.testOnRuns = before.runMedians.size() >= 2 && after.runMedians.size() >= 2;
  if (row.testOnRuns) {
    row.test = mannWhitneyU(after.runMedians, before.runMedians);  // "after tends to be larger" = slower
  } else if (singleRuns) {
    row.test = mannWhitneyU(after.frames.front(), before.frames.front());
  }
  row.verdict = judge(row, o, singleRuns);
  return row;
}

PassComparison marker(const std::string& pass, const char* verdict) {
  PassComparison row;
  row.pass = pass;
  row.verdict = verdict;
  return row;
}

}  // namespace

bool RunsComparison::anySlower() const {
  return std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict == "slower"; });
}

bool RunsComparison::anyUnknown() const {
  return std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict == "unknown"; });
}

std::string RunsComparison::verdict() const { return anySlower() ? "slower" : anyUnknown() ? "unknown" : "same"; }

RunsComparison compareRuns(const LoadedTimings& before, const LoadedTimings& after, const CompareRunsOptions& options) {
  return compareRuns(std::vector<LoadedTimings>{before}, std::vector<LoadedTimings>{after}, options);
}

namespace {

// Each frame's GPU time over a side's runs (geometric mean); empty when the runs' path times differ.
std::vector<double> pathFrameMeans(const std::vector<LoadedTimings>& runs, const std::vector<double>& times) {
  std::vector<double> logSum(times.size(), 0.0);
  for (const auto& run : runs) {
    if (run.framePathTimeS != times || run.frameGpuMs.size() != times.size()) return {};
    for (std::size_t f = 0; f < times.size(); ++f) logSum[f] += std::log(std::max(run.frameGpuMs[f], 1e-9));
  }
  for (double& value : logSum) value = std::exp(value / static_cast<double>(runs.size()));
  return logSum;
}

std::vector<PathFrameComparison> comparePathFrames(const std::vector<LoadedTimings>& before,
                                                   const std::vector<LoadedTimings>& after) {
  const std::vector<double>& times = after.front().framePathTimeS;
  if (times.empty()) return {};
  const auto old = pathFrameMeans(before, times), now = pathFrameMeans(after, times);
  if (old.empty() || now.empty()) return {};
  std::vector<PathFrameComparison> frames;
  for (std::size_t f = 0; f < times.size(); ++f) frames.push_back({f, times[f], old[f], now[f]});
  return frames;
}

}  // namespace

RunsComparison compareRuns(const std::vector<LoadedTimings>& before, const std::vector<LoadedTimings>& after,
                           const CompareRunsOptions& options) {
  if (before.empty() || after.empty()) throw InputError("compare-runs: each side needs at least one run");
  RunsComparison result;
  result.options = options;
  result.beforeRuns = before.size();
  result.afterRuns = after.size();

  // The noise model: the one asked for, else the runs' device type (the noisier one when they differ).
  std::string deviceClass = options.deviceClass;
  if (deviceClass.empty()) {
    for (const auto* side : {&before, &after}) {
      for (const auto& run : *side) {
        if (deviceClass.empty() || runNoiseFor(run.deviceType).relative > runNoiseFor(deviceClass).relative)
          deviceClass = run.deviceType;
      }
    }
  }
  result.model = runNoiseFor(deviceClass);
  if (options.runNoise >= 0.0) {
    result.model.relative = options.runNoise;
    result.model.measured = "--run-noise";
  }
  if (before.front().deviceName != after.front().deviceName) {
    result.warnings.push_back(
        fmt::format("comparing different devices ({} vs {})", before.front().deviceName, after.front().deviceName));
  }
  if (before.size() < kRecommendedRuns || after.size() < kRecommendedRuns) {
    result.warnings.push_back(fmt::format(
        "{} vs {} runs: fewer than {} a side, so verdicts lean on the '{}' noise model ({:.1f}% run to run); "
        "bench/ab-runs.sh makes interleaved repetitions",
        before.size(), after.size(), kRecommendedRuns, result.model.deviceClass, result.model.relative * 100.0));
  }

  // Passes in the order of the first new run, then those only the old runs have.
  std::vector<std::string> names;
  const auto addName = [&](const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  };
  for (const auto& run : after)
    for (const auto& p : run.passes) addName(p.name);
  for (const auto& run : before)
    for (const auto& p : run.passes) addName(p.name);

  const bool beforeIsolated = everyRunIsolated(before), afterIsolated = everyRunIsolated(after);
  result.passCost = beforeIsolated && afterIsolated ? "isolated" : "span";
  if (result.passCost == "span" && (beforeIsolated || afterIsolated)) {
    result.warnings.push_back(
        "passes judged by their spans: the runs of one side have no isolated costs (older timings.json files or "
        "runs with --no-isolate)");
  }
  const bool isolated = result.passCost == "isolated";
  for (const auto& name : names) {
    const Side old = passSide(before, name, isolated);
    const Side now = passSide(after, name, isolated);
    if (old.runMedians.empty() && !old.culled) {
      PassComparison row = marker(name, "added");
      row.after = summarize(now.frames.empty() ? std::vector<double>{} : now.frames.front());
      result.rows.push_back(row);
    } else if (now.runMedians.empty() && !now.culled) {
      PassComparison row = marker(name, "removed");
      row.before = summarize(old.frames.empty() ? std::vector<double>{} : old.frames.front());
      result.rows.push_back(row);
    } else if (old.culled || now.culled || old.missing || now.missing) {
      result.rows.push_back(marker(name, "culled"));
    } else {
      result.rows.push_back(compareSides(name, old, now, result.model, options));
    }
  }
  const Side oldFrame = frameSide(before);
  const Side newFrame = frameSide(after);
  if (!oldFrame.culled && !newFrame.culled && !oldFrame.runMedians.empty() && !newFrame.runMedians.empty()) {
    result.rows.push_back(compareSides("(frame)", oldFrame, newFrame, result.model, options));
  }
  result.pathFrames = comparePathFrames(before, after);
  return result;
}

// --- inputs ---

namespace {

// Natural order: digit runs compare as numbers (r2 < r10).
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      const std::string na = a.substr(i, ei - i), nb = b.substr(j, ej - j);
      const std::size_t za = na.find_first_not_of('0'), zb = nb.find_first_not_of('0');
      const std::string ta = za == std::string::npos ? "" : na.substr(za);
      const std::string tb = zb == std::string::npos ? "" : nb.substr(zb);
      if (ta.size() != tb.size()) return ta.size() < tb.size();
      if (ta != tb) return ta < tb;
      i = ei;
      j = ej;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

std::vector<std::filesystem::path> timingsFilesIn(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(path, error)) throw InputError(path.string() + ": no such file or directory");
  if (!fs::is_directory(path, error)) return {path};
  if (fs::is_regular_file(path / "timings.json", error)) return {path / "timings.json"};
  std::vector<fs::path> found;
  for (const auto& entry : fs::directory_iterator(path, error)) {
    if (entry.is_directory(error) && fs::is_regular_file(entry.path() / "timings.json", error)) {
      found.push_back(entry.path() / "timings.json");
    } else if (entry.is_regular_file(error) && entry.path().extension() == ".json") {
      found.push_back(entry.path());
    }
  }
  if (error) throw InputError(path.string() + ": cannot list the directory: " + error.message());
  if (found.empty()) {
    throw InputError(path.string() + ": no timings.json in it, in its subfolders, nor *.json files");
  }
  std::sort(found.begin(), found.end(),
            [](const fs::path& a, const fs::path& b) { return naturalLess(a.string(), b.string()); });
  return found;
}

// --- output ---

std::string formatTable(const RunsComparison& c) {
  std::size_t nameWidth = 4;
  for (const auto& r : c.rows) nameWidth = std::max(nameWidth, r.pass.size());
  std::string out = fmt::format("{:<{}}  {:>10}  {:>10}  {:>10}  {:>8}  {:>6}  {:>10}  {:>9}  {}\n", "pass", nameWidth,
                                "old ms", "new ms", "delta ms", "delta", "noise", "detectable", "p(slower)", "verdict");
  for (const auto& r : c.rows) {
    if (r.verdict == "added" || r.verdict == "removed" || r.verdict == "culled") {
      out += fmt::format("{:<{}}  {:>10}  {:>10}  {:>10}  {:>8}  {:>6}  {:>10}  {:>9}  {}\n", r.pass, nameWidth,
                         r.verdict == "added" ? "-" : fmt::format("{:.4f}", r.before.median),
                         r.verdict == "removed" ? "-" : fmt::format("{:.4f}", r.after.median), "-", "-", "-", "-", "-",
                         r.verdict);
      continue;
    }
    // Passes of a few microseconds have no usable relative noise or detectable change.
    const auto percent = [](double fraction, int width) {
      return fraction < 10.0 ? fmt::format("{:>{}.1f}%", fraction * 100.0, width - 1)
                             : fmt::format("{:>{}}", ">999%", width);
    };
    out +=
        fmt::format("{:<{}}  {:>10.4f}  {:>10.4f}  {:>+10.4f}  {:>+7.1f}%  {}  {}  {:>9.2g}  {}\n", r.pass, nameWidth,
                    r.before.median, r.after.median, r.deltaMs, r.deltaRelative * 100.0, percent(r.noise, 6),
                    percent(r.detectable, 10), r.pSlower, r.verdict == "unknown" ? "unknown: add runs" : r.verdict);
  }
  out += fmt::format(
      "({} vs {} runs; per pass each run's median{}, geometric mean over runs; one-sided test of the log change "
      "against "
      "the run-to-run noise (the runs' own, or the '{}' model's {:.1f}% + {} ms when larger), alpha {}; a change "
      "counts when >= {:.1f}% and >= {} ms; detectable: the change found with probability {})\n",
      c.beforeRuns, c.afterRuns,
      c.passCost == "isolated" ? " isolated cost (each pass alone on an idle device)" : " span", c.model.deviceClass,
      c.model.relative * 100.0, c.model.absoluteMs, c.options.alpha, c.options.minEffect * 100.0, c.options.minAbsMs,
      c.options.power);
  std::string unknown;
  for (const auto& r : c.rows) {
    if (r.verdict == "unknown") unknown += fmt::format(" {} {:+.1f}%;", r.pass, r.deltaRelative * 100.0);
  }
  if (!unknown.empty())
    out += "unknown: add runs (changes that would matter, inside the run-to-run noise):" + unknown + "\n";
  if (!c.pathFrames.empty()) {
    // The frames whose time changed most, either way, with the path time to render them alone.
    std::vector<PathFrameComparison> sorted = c.pathFrames;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
      return std::abs(std::log(std::max(a.ratio(), 1e-9))) > std::abs(std::log(std::max(b.ratio(), 1e-9)));
    });
    std::vector<double> ratios;
    for (const auto& frame : c.pathFrames) ratios.push_back(frame.ratio());
    std::sort(ratios.begin(), ratios.end());
    out += fmt::format("camera path, frame by frame ({} frames, new/old GPU frame time): median {:.3f}, {:.3f} .. {:.3f}; "
                       "most changed:",
                       ratios.size(), ratios[ratios.size() / 2], ratios.front(), ratios.back());
    for (std::size_t i = 0; i < std::min<std::size_t>(3, sorted.size()); ++i) {
      out += fmt::format(" frame {} (t={:g} s) {:.4f} -> {:.4f} ms;", sorted[i].frame, sorted[i].pathTimeS,
                         sorted[i].beforeMs, sorted[i].afterMs);
    }
    out += "\n";
  }
  for (const auto& warning : c.warnings) out += "note: " + warning + "\n";
  return out;
}

namespace {
nlohmann::json pathFramesJson(const RunsComparison& c) {
  nlohmann::json frames = nlohmann::json::array();
  for (const auto& f : c.pathFrames) {
    frames.push_back({{"frame", f.frame}, {"path_time_s", f.pathTimeS}, {"old_ms", f.beforeMs}, {"new_ms", f.afterMs},
                      {"ratio", f.ratio()}});
  }
  return frames;
}
}  // namespace

nlohmann::json toJson(const RunsComparison& c) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : c.rows) {
    rows.push_back({{"pass", r.pass},
                    {"old_median_ms", r.before.median},
                    {"new_median_ms", r.after.median},
                    {"old_n", r.before.n},
                    {"new_n", r.after.n},
                    {"delta_ms", r.deltaMs},
                    {"delta_relative", r.deltaRelative},
                    {"u", r.test.uA},
                    {"p_slower", r.pSlower},
                    {"p_faster", r.pFaster},
                    {"exact", r.test.exact},
                    {"verdict", r.verdict},
                    {"old_runs", r.beforeRuns.size()},
                    {"new_runs", r.afterRuns.size()},
                    {"old_run_medians_ms", r.beforeRuns},
                    {"new_run_medians_ms", r.afterRuns},
                    {"noise_relative", r.noise},
                    {"noise_source", r.noiseFromRuns ? "runs" : "model"},
                    {"band_relative", r.band},
                    {"detectable_relative", r.detectable},
                    {"u_on", r.testOnRuns ? "runs" : "frames"},
                    {"u_p_slower", r.test.pAGreater},
                    {"u_p_faster", r.test.pALess}});
  }
  return {{"alpha", c.options.alpha},
          {"min_effect", c.options.minEffect},
          {"min_abs_ms", c.options.minAbsMs},
          {"power", c.options.power},
          {"regression", c.anySlower()},
          {"verdict", c.verdict()},
          {"old_runs", c.beforeRuns},
          {"new_runs", c.afterRuns},
          {"noise_model",
           {{"device_class", c.model.deviceClass},
            {"relative", c.model.relative},
            {"absolute_ms", c.model.absoluteMs},
            {"measured", c.model.measured}}},
          {"warnings", c.warnings},
          {"path_frames", pathFramesJson(c)},
          {"passes", rows}};
}

}  // namespace fgb::harness
