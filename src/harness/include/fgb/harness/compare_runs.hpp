// Run-to-run regression test between two timings.json files: per pass, a one-sided Mann–Whitney U
// test on the per-frame samples plus a minimum effect size, so that neither noise nor a
// statistically "significant" 0.1% change counts as a regression.
#pragma once

#include <fgb/harness/mann_whitney.hpp>
#include <fgb/harness/stats.hpp>
#include <fgb/harness/timings.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fgb::harness {

struct CompareRunsOptions {
  double alpha = 0.01;       // one-sided significance level
  double minEffect = 0.05;   // relative change of the median that matters (5%)
  double minAbsMs = 0.01;    // and in absolute terms: smaller shifts are timer and scheduling noise
};

struct PassComparison {
  std::string pass;  // "(frame)" for the whole frame
  Summary before, after;
  double deltaMs = 0.0;
  double deltaRelative = 0.0;  // after.median / before.median - 1
  MannWhitneyResult test;
  std::string verdict;  // "slower" | "faster" | "same" | "added" | "removed" | "culled"
};

struct RunsComparison {
  std::vector<PassComparison> rows;
  CompareRunsOptions options;
  bool anySlower() const;
};

RunsComparison compareRuns(const LoadedTimings& before, const LoadedTimings& after, const CompareRunsOptions& options = {});

std::string formatTable(const RunsComparison& comparison);
nlohmann::json toJson(const RunsComparison& comparison);

}  // namespace fgb::harness
