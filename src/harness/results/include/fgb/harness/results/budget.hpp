// Per-pass millisecond budgets (bench/budgets/*.json) and the check of measured medians against them.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

struct Budget {
  std::string file;
  std::string name;
  std::string deviceName;
  uint32_t width = 0, height = 0, msaa = 0;  // what the budget was measured at (0: unspecified)
  double tolerance = 0.10;                   // relative: a pass fails above budget * (1 + tolerance)
  std::vector<std::pair<std::string, double>> passesMs;  // in file order
  std::optional<double> frameMs;
  // frame_p99_ms: the 99th percentile of the GPU frame time (along a camera path, the slow frames).
  std::optional<double> frameP99Ms;
};

// Throws InputError naming the file and field on any problem.
Budget loadBudget(const std::filesystem::path& path);

struct BudgetLine {
  std::string pass;  // "(frame)" for the whole frame
  double budgetMs = 0.0;
  double limitMs = 0.0;  // budget * (1 + tolerance)
  std::optional<double> measuredMs;  // median; empty when the pass was not measured (absent or culled)
  std::string status;  // "ok" | "over" | "missing"
  std::size_t summedPasses = 0;  // > 0: no pass has the budget's name; the sum of "<name> ..." passes
  double overMs() const { return measuredMs ? *measuredMs - budgetMs : 0.0; }
  double overPercent() const { return measuredMs && budgetMs > 0 ? (*measuredMs / budgetMs - 1.0) * 100.0 : 0.0; }
};

struct BudgetResult {
  std::string file;
  std::string verdict = "none";  // "pass" | "fail" | "none"
  double tolerance = 0.0;
  std::vector<BudgetLine> lines;
  std::string passCost = "span";      // what the pass lines judged: "isolated" costs or "span"s
  std::vector<std::string> warnings;  // e.g. resolution differs from the budget's

  std::vector<const BudgetLine*> failing() const;
  // "judged on isolated costs" or "judged on spans (the run has no isolated costs: --no-isolate or
  // an older timings.json)", for the terminal and the reports.
  [[nodiscard]] std::string judgedOn() const;
};

struct MeasuredMedians {
  std::map<std::string, double> passMs;  // measured (not culled) passes only
  std::string passCost = "span";         // "isolated" where the run was calibrated, else "span"
  std::optional<double> frameMs;
  std::optional<double> frameP99Ms;  // p99 of the GPU frame time
  uint32_t width = 0, height = 0, msaa = 0;
};

// tolerance < 0 keeps the budget file's tolerance. A budget names a pass, or a group of passes a
// renderer splits it into ("X" = "X Downsample 1" + "X Upsample 1" + ... when no pass is called "X"):
// then the sum of their medians is checked. A line fails when over the limit or not measured; the
// verdict is "fail" if any line fails.
BudgetResult checkBudget(const Budget& budget, const MeasuredMedians& measured, double tolerance = -1.0);

// The contract's timings.json "budget" object.
nlohmann::json toJson(const BudgetResult& result);

}  // namespace fgb::harness
