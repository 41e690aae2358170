#include <fgb/harness/compare_runs.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fgb::harness {
namespace {

std::string judge(const PassComparison& row, const CompareRunsOptions& o) {
  const bool bigEnough = std::abs(row.deltaRelative) >= o.minEffect && std::abs(row.deltaMs) >= o.minAbsMs;
  if (bigEnough && row.deltaMs > 0 && row.test.pAGreater < o.alpha) return "slower";
  if (bigEnough && row.deltaMs < 0 && row.test.pALess < o.alpha) return "faster";
  return "same";
}

PassComparison compareSamples(std::string name, const std::vector<double>& before, const std::vector<double>& after,
                              const CompareRunsOptions& options) {
  PassComparison row;
  row.pass = std::move(name);
  row.before = summarize(before);
  row.after = summarize(after);
  row.deltaMs = row.after.median - row.before.median;
  row.deltaRelative = row.before.median > 0 ? row.after.median / row.before.median - 1.0 : 0.0;
  row.test = mannWhitneyU(after, before);  // "after tends to be larger" = slower
  row.verdict = judge(row, options);
  return row;
}

const PassRecord* find(const LoadedTimings& t, const std::string& name) {
  for (const auto& p : t.passes) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace

bool RunsComparison::anySlower() const {
  return std::any_of(rows.begin(), rows.end(), [](const auto& r) { return r.verdict == "slower"; });
}

RunsComparison compareRuns(const LoadedTimings& before, const LoadedTimings& after, const CompareRunsOptions& options) {
  RunsComparison result;
  result.options = options;
  for (const auto& pass : after.passes) {
    const PassRecord* old = find(before, pass.name);
    if (!old) {
      PassComparison row;
      row.pass = pass.name;
      row.after = pass.gpu;
      row.verdict = "added";
      result.rows.push_back(row);
    } else if (pass.culled || old->culled || pass.samplesMs.empty() || old->samplesMs.empty()) {
      PassComparison row;
      row.pass = pass.name;
      row.verdict = "culled";
      result.rows.push_back(row);
    } else {
      result.rows.push_back(compareSamples(pass.name, old->samplesMs, pass.samplesMs, options));
    }
  }
  for (const auto& pass : before.passes) {
    if (!find(after, pass.name)) {
      PassComparison row;
      row.pass = pass.name;
      row.before = pass.gpu;
      row.verdict = "removed";
      result.rows.push_back(row);
    }
  }
  if (!before.frameGpuMs.empty() && !after.frameGpuMs.empty()) {
    result.rows.push_back(compareSamples("(frame)", before.frameGpuMs, after.frameGpuMs, options));
  }
  return result;
}

std::string formatTable(const RunsComparison& c) {
  std::size_t nameWidth = 4;
  for (const auto& r : c.rows) nameWidth = std::max(nameWidth, r.pass.size());
  std::string out = fmt::format("{:<{}}  {:>10}  {:>10}  {:>10}  {:>8}  {:>9}  {}\n", "pass", nameWidth, "old ms",
                                "new ms", "delta ms", "delta", "p(slower)", "verdict");
  for (const auto& r : c.rows) {
    if (r.verdict == "added" || r.verdict == "removed" || r.verdict == "culled") {
      out += fmt::format("{:<{}}  {:>10}  {:>10}  {:>10}  {:>8}  {:>9}  {}\n", r.pass, nameWidth,
                         r.verdict == "added" ? "-" : fmt::format("{:.4f}", r.before.median),
                         r.verdict == "removed" ? "-" : fmt::format("{:.4f}", r.after.median), "-", "-", "-", r.verdict);
      continue;
    }
    out += fmt::format("{:<{}}  {:>10.4f}  {:>10.4f}  {:>+10.4f}  {:>+7.1f}%  {:>9.2g}  {}\n", r.pass, nameWidth,
                       r.before.median, r.after.median, r.deltaMs, r.deltaRelative * 100.0, r.test.pAGreater, r.verdict);
  }
  out += fmt::format("(one-sided Mann-Whitney U, alpha {}; a change counts when >= {:.1f}% and >= {} ms)\n",
                     c.options.alpha, c.options.minEffect * 100.0, c.options.minAbsMs);
  return out;
}

nlohmann::json toJson(const RunsComparison& c) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : c.rows) {
    rows.push_back({{"pass", r.pass}, {"old_median_ms", r.before.median}, {"new_median_ms", r.after.median},
                    {"old_n", r.before.n}, {"new_n", r.after.n}, {"delta_ms", r.deltaMs},
                    {"delta_relative", r.deltaRelative}, {"u", r.test.uA}, {"p_slower", r.test.pAGreater},
                    {"p_faster", r.test.pALess}, {"exact", r.test.exact}, {"verdict", r.verdict}});
  }
  return {{"alpha", c.options.alpha}, {"min_effect", c.options.minEffect}, {"min_abs_ms", c.options.minAbsMs},
          {"regression", c.anySlower()}, {"passes", rows}};
}

}  // namespace fgb::harness
