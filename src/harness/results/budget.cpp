#include <fgb/harness/results/budget.hpp>

#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>

#include <cmath>

namespace fgb::harness {
namespace {

double requirePositiveMs(const nlohmann::json& object, const std::string& key, const std::filesystem::path& file,
                         const std::string& where) {
  const double value = requireNumber(object, key, file, where);
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError(file.string() + ": field '" + where + "." + key + "' must be a positive number of milliseconds");
  }
  return value;
}

BudgetLine judge(std::string pass, double budgetMs, double tolerance, std::optional<double> measured) {
  BudgetLine line;
  line.pass = std::move(pass);
  line.budgetMs = budgetMs;
  line.limitMs = budgetMs * (1.0 + tolerance);
  line.measuredMs = measured;
  line.status = !measured ? "missing" : (*measured > line.limitMs ? "over" : "ok");
  return line;
}

// The measured median for a budget entry: the pass of that name, else the sum over passes named
// "<name> <anything>" (a feature split into several passes).
std::pair<std::optional<double>, std::size_t> measuredFor(const std::string& name, const std::map<std::string, double>& passes) {
  if (const auto it = passes.find(name); it != passes.end()) return {it->second, 0};
  double sum = 0.0;
  std::size_t count = 0;
  for (const auto& [pass, ms] : passes) {
    if (pass.size() > name.size() + 1 && pass.starts_with(name) && pass[name.size()] == ' ') {
      sum += ms;
      ++count;
    }
  }
  if (count == 0) return {std::nullopt, 0};
  return {sum, count};
}

}  // namespace

Budget loadBudget(const std::filesystem::path& path) {
  const nlohmann::json j = readJsonFile(path);
  Budget budget;
  budget.file = path.string();
  if (!j.is_object()) throw InputError(path.string() + ": a budget must be a JSON object");
  budget.name = optionalString(j, "name", path.stem().string(), path);
  if (j.contains("device")) budget.deviceName = optionalString(j["device"], "name", "", path, "device");
  if (j.contains("config")) {
    const auto& config = j["config"];
    budget.width = static_cast<uint32_t>(optionalNumber(config, "width", 0, path, "config"));
    budget.height = static_cast<uint32_t>(optionalNumber(config, "height", 0, path, "config"));
    budget.msaa = static_cast<uint32_t>(optionalNumber(config, "msaa", 0, path, "config"));
  }
  budget.tolerance = optionalNumber(j, "tolerance", budget.tolerance, path);
  if (!(budget.tolerance >= 0.0 && budget.tolerance < 10.0)) {
    throw InputError(path.string() + ": field 'tolerance' must be a fraction in [0, 10)");
  }
  const auto& passes = requireField(j, "passes_ms", path);
  if (!passes.is_object() || passes.empty()) {
    throw InputError(path.string() + ": field 'passes_ms' must be a non-empty object of pass name -> ms");
  }
  // Keep the file's pass order (the table's order) for reports.
  const nlohmann::ordered_json ordered = readOrderedJsonFile(path);
  for (const auto& [name, value] : ordered["passes_ms"].items()) {
    budget.passesMs.emplace_back(name, requirePositiveMs(passes, name, path, "passes_ms"));
  }
  if (j.contains("frame_ms")) budget.frameMs = requirePositiveMs(j, "frame_ms", path, "");
  if (j.contains("frame_p99_ms")) budget.frameP99Ms = requirePositiveMs(j, "frame_p99_ms", path, "");
  return budget;
}

std::vector<const BudgetLine*> BudgetResult::failing() const {
  std::vector<const BudgetLine*> out;
  for (const auto& line : lines) {
    if (line.status != "ok") out.push_back(&line);
  }
  return out;
}

BudgetResult checkBudget(const Budget& budget, const MeasuredMedians& measured, double tolerance) {
  BudgetResult result;
  result.file = budget.file;
  result.tolerance = tolerance >= 0.0 ? tolerance : budget.tolerance;
  result.passCost = measured.passCost;
  for (const auto& [pass, ms] : budget.passesMs) {
    const auto [median, summed] = measuredFor(pass, measured.passMs);
    result.lines.push_back(judge(pass, ms, result.tolerance, median));
    result.lines.back().summedPasses = summed;
  }
  if (budget.frameMs) result.lines.push_back(judge("(frame)", *budget.frameMs, result.tolerance, measured.frameMs));
  if (budget.frameP99Ms) {
    result.lines.push_back(judge("(frame p99)", *budget.frameP99Ms, result.tolerance, measured.frameP99Ms));
  }

  if (budget.width && measured.width && (budget.width != measured.width || budget.height != measured.height)) {
    result.warnings.push_back("budget measured at " + std::to_string(budget.width) + "x" + std::to_string(budget.height) +
                              ", run at " + std::to_string(measured.width) + "x" + std::to_string(measured.height));
  }
  if (budget.msaa && measured.msaa && budget.msaa != measured.msaa) {
    result.warnings.push_back("budget measured with MSAA " + std::to_string(budget.msaa) + ", run with MSAA " +
                              std::to_string(measured.msaa));
  }
  result.verdict = result.failing().empty() ? "pass" : "fail";
  return result;
}

std::string BudgetResult::judgedOn() const {
  return passCost == "isolated" ? "passes judged on isolated costs"
                                : "passes judged on spans (no isolated costs in this run: --no-isolate, or a "
                                  "timings.json from before the calibration)";
}

nlohmann::json toJson(const BudgetResult& result) {
  nlohmann::json over = nlohmann::json::array();
  nlohmann::json lines = nlohmann::json::array();
  for (const auto& line : result.lines) {
    nlohmann::json entry{{"pass", line.pass}, {"budget_ms", line.budgetMs}, {"limit_ms", line.limitMs},
                         {"measured_ms", line.measuredMs ? nlohmann::json(*line.measuredMs) : nlohmann::json(nullptr)},
                         {"status", line.status}};
    if (line.summedPasses > 0) entry["summed_passes"] = line.summedPasses;
    if (line.measuredMs) {
      entry["over_ms"] = line.overMs();
      entry["over_percent"] = line.overPercent();
    }
    if (line.status != "ok") over.push_back(entry);
    lines.push_back(std::move(entry));
  }
  return {{"file", result.file},
          {"verdict", result.verdict},
          {"tolerance", result.tolerance},
          {"pass_cost", result.passCost},
          {"over", over},
          {"lines", lines},
          {"warnings", result.warnings}};
}

}  // namespace fgb::harness
