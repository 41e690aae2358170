// The sweep's grid: --vary axes, sweep files, the grid's expansion and the reference configuration.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/sweep/sweep.hpp>
#include <stdexcept>

namespace fgb::harness {
namespace {

std::vector<std::string> splitList(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

std::optional<uint32_t> parsePositive(const std::string& text) {
  uint32_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || value == 0 || value > 16384) return std::nullopt;
  return value;
}

std::optional<std::pair<uint32_t, uint32_t>> parseSize(const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  const auto w = parsePositive(text.substr(0, x)), h = parsePositive(text.substr(x + 1));
  if (!w || !h) return std::nullopt;
  return std::pair{*w, *h};
}

// Empty when `value` suits `key`, else what was expected. Knobs are checked by the renderer's
// knob registry when the configuration is opened (before anything is measured).
std::string expectedFor(const std::string& key, const std::string& value) {
  if (key == "msaa") return (value == "1" || value == "2" || value == "4" || value == "8") ? "" : "1|2|4|8";
  if (key == "width" || key == "height") return parsePositive(value) ? "" : "a positive integer up to 16384";
  if (key == "size") return parseSize(value) ? "" : "WIDTHxHEIGHT, e.g. 640x360";
  return "";
}

void apply(render::WorkloadConfig& config, const std::string& key, const std::string& value) {
  if (key == "msaa") {
    config.msaa = *parsePositive(value);
  } else if (key == "width") {
    config.width = *parsePositive(value);
  } else if (key == "height") {
    config.height = *parsePositive(value);
  } else if (key == "size") {
    std::tie(config.width, config.height) = *parseSize(value);
  } else {
    config.knobs[key] = value;
  }
}

SweepAxis checkedAxis(const std::string& key, const std::vector<std::string>& values, const std::string& where) {
  if (key.empty()) throw InputError(where + ": empty key (expected KEY=V1,V2,...)");
  if (key.find_first_of(" \t,") != std::string::npos) throw InputError(where + ": malformed key '" + key + "'");
  if (values.empty()) throw InputError(where + ": no values (expected KEY=V1,V2,...)");
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i].empty()) throw InputError(where + ": empty value (expected KEY=V1,V2,...)");
    if (std::find(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(i), values[i]) !=
        values.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw InputError(where + ": value '" + values[i] + "' given twice");
    }
    const std::string expected = expectedFor(key, values[i]);
    if (!expected.empty())
      throw InputError(where + ": " + key + "=" + values[i] + " is not valid (expected " + expected + ")");
  }
  return {key, values};
}

std::string jsonScalarText(const nlohmann::json& v, const std::string& where) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<int64_t>());
  if (v.is_number()) return fmt::format("{}", v.get<double>());
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  throw InputError(where + " must be a string or a number");
}

}  // namespace

SweepAxis parseVary(const std::string& text) {
  const std::string where = "--vary " + text;
  const auto eq = text.find('=');
  if (eq == std::string::npos) throw InputError(where + ": expected KEY=V1,V2,...");
  return checkedAxis(text.substr(0, eq), splitList(text.substr(eq + 1), ','), where);
}

SweepFile loadSweepFile(const std::filesystem::path& path) {
  const nlohmann::json j = readJsonFile(path);
  const std::string file = path.string();
  if (!j.is_object()) throw InputError(file + ": expected a JSON object");
  if (requireNumber(j, "schema", path) != 1) throw InputError(file + ": field 'schema' must be 1");
  SweepFile sweep;
  sweep.description = optionalString(j, "description", "", path);
  const auto& vary = requireField(j, "vary", path);
  if (!vary.is_array()) throw InputError(file + ": field 'vary' must be an array of {\"key\", \"values\"}");
  for (std::size_t i = 0; i < vary.size(); ++i) {
    const std::string where = fmt::format("vary[{}]", i);
    const std::string key = requireString(vary[i], "key", path, where);
    const auto& values = requireField(vary[i], "values", path, where);
    if (!values.is_array()) throw InputError(file + ": field '" + where + ".values' must be an array");
    std::vector<std::string> texts;
    for (std::size_t k = 0; k < values.size(); ++k) {
      texts.push_back(jsonScalarText(values[k], fmt::format("{}: field '{}.values[{}]'", file, where, k)));
    }
    sweep.axes.push_back(checkedAxis(key, texts, file + ": " + where));
  }
  if (j.contains("set")) {
    if (!j["set"].is_object()) throw InputError(file + ": field 'set' must be an object of knobs");
    for (const auto& [key, value] : j["set"].items())
      sweep.knobs[key] = jsonScalarText(value, file + ": field 'set." + key + "'");
  }
  sweep.width = static_cast<uint32_t>(optionalNumber(j, "width", 0, path));
  sweep.height = static_cast<uint32_t>(optionalNumber(j, "height", 0, path));
  return sweep;
}

std::vector<SweepConfiguration> expandGrid(const render::WorkloadConfig& base, const std::vector<SweepAxis>& axes) {
  if (axes.empty()) throw InputError("sweep: nothing to vary (give --vary KEY=V1,V2,... or --sweep FILE)");
  std::size_t count = 1;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    for (std::size_t b = 0; b < a; ++b) {
      const bool sizeClash = (axes[a].key == "size" && (axes[b].key == "width" || axes[b].key == "height")) ||
                             (axes[b].key == "size" && (axes[a].key == "width" || axes[a].key == "height"));
      if (axes[a].key == axes[b].key || sizeClash) {
        throw InputError("--vary " + axes[a].key + ": varied twice (also as --vary " + axes[b].key + ")");
      }
    }
    count *= axes[a].values.size();
    if (count > kMaxSweepConfigurations) {
      throw InputError(
          fmt::format("sweep: the grid has more than {} configurations; vary fewer values", kMaxSweepConfigurations));
    }
  }
  std::vector<SweepConfiguration> grid;
  std::vector<std::size_t> digit(axes.size(), 0);  // mixed-radix counter over the axes' values
  for (std::size_t n = 0; n < count; ++n) {
    SweepConfiguration c;
    c.workload = base;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const std::string& value = axes[a].values[digit[a]];
      apply(c.workload, axes[a].key, value);
      c.point.emplace_back(axes[a].key, value);
      c.label += (c.label.empty() ? "" : " ") + axes[a].key + "=" + value;
    }
    grid.push_back(std::move(c));
    for (std::size_t a = axes.size(); a-- > 0;) {
      if (++digit[a] < axes[a].values.size()) break;
      digit[a] = 0;
    }
  }
  return grid;
}

bool isKnobAxis(const std::string& key) {
  return key != "msaa" && key != "width" && key != "height" && key != "size";
}

ReferenceRole roleOf(const ReferenceRules& rules, const std::string& key) {
  if (key == "msaa") return ReferenceRole::Approximation;
  if (!isKnobAxis(key) || !rules.knobs) return ReferenceRole::Content;
  const KnobSpec* spec = rules.knobs->find(key);
  if (!spec) throw std::logic_error("sweep: knob '" + key + "' is not in the knob registry");
  return spec->role;
}

render::WorkloadConfig referenceOf(const SweepConfiguration& configuration, const ReferenceRules& rules) {
  render::WorkloadConfig reference = configuration.workload;
  reference.msaa = rules.msaa;
  reference.clampMsaaToPath = true;
  std::map<std::string, std::string> knobs;
  for (const auto& [key, value] : configuration.workload.knobs) {
    switch (roleOf(rules, key)) {
      case ReferenceRole::Look: {
        // A varied look knob is judged against the base's value (the scene's own where unset).
        const bool varied = std::any_of(configuration.point.begin(), configuration.point.end(),
                                        [&](const auto& axis) { return axis.first == key; });
        const auto base = rules.baseKnobs.find(key);
        if (!varied) {
          knobs.insert_or_assign(key, value);
        } else if (base != rules.baseKnobs.end()) {
          knobs.insert_or_assign(key, base->second);
        }
        break;
      }
      case ReferenceRole::Content:
        knobs.insert_or_assign(key, value);
        break;
      case ReferenceRole::Approximation:
      case ReferenceRole::CostOnly:
      case ReferenceRole::Unset:
        break;  // set from the registry below
    }
  }
  // Every approximation at its exact value and every cost-only knob at its pinned one, whether the
  // configuration set it or not: so the reference does not depend on which of them a sweep varied.
  if (rules.knobs) {
    for (const KnobSpec& spec : rules.knobs->specs()) {
      const bool pinned = spec.role == ReferenceRole::CostOnly && !spec.exact.empty();
      if (spec.role == ReferenceRole::Approximation || pinned) knobs.insert_or_assign(spec.key, spec.exact);
    }
  }
  knobs.insert_or_assign("render.ssaa", std::to_string(rules.ssaa));
  reference.knobs = std::move(knobs);
  return reference;
}

std::optional<render::WorkloadConfig> convergenceStepOf(const render::WorkloadConfig& reference) {
  const auto ssaa = reference.knobs.find("render.ssaa");
  const std::optional<uint32_t> factor = ssaa == reference.knobs.end() ? std::nullopt : parsePositive(ssaa->second);
  if (!factor || *factor < 2) return std::nullopt;
  render::WorkloadConfig step = reference;
  step.knobs.insert_or_assign("render.ssaa", std::to_string(*factor - 1));
  return step;
}

namespace {

// The configuration's varied cost-only knobs whose values differ from the reference's.
std::vector<std::pair<std::string, std::string>> biasKnobs(const SweepConfiguration& configuration,
                                                           const ReferenceRules& rules) {
  std::vector<std::pair<std::string, std::string>> knobs;
  if (!rules.knobs) return knobs;
  for (const auto& [key, value] : configuration.point) {
    const KnobSpec* spec = rules.knobs->find(key);
    if (spec && spec->role == ReferenceRole::CostOnly && value != spec->exact) knobs.emplace_back(key, value);
  }
  return knobs;
}

}  // namespace

std::optional<render::WorkloadConfig> biasRenderOf(const SweepConfiguration& configuration,
                                                   const render::WorkloadConfig& reference,
                                                   const ReferenceRules& rules) {
  const auto knobs = biasKnobs(configuration, rules);
  if (knobs.empty()) return std::nullopt;
  render::WorkloadConfig bias = reference;
  for (const auto& [key, value] : knobs) bias.knobs.insert_or_assign(key, value);
  return bias;
}

std::string biasLabelOf(const SweepConfiguration& configuration, const ReferenceRules& rules) {
  std::string label;
  for (const auto& [key, value] : biasKnobs(configuration, rules))
    label += (label.empty() ? "" : " ") + key + "=" + value;
  return label;
}

std::vector<std::string> variedLookKeys(const std::vector<SweepConfiguration>& configurations,
                                        const ReferenceRules& rules) {
  std::vector<std::string> keys;
  if (configurations.empty()) return keys;
  for (const auto& [key, value] : configurations.front().point) {
    if (roleOf(rules, key) == ReferenceRole::Look) keys.push_back(key);
  }
  return keys;
}

}  // namespace fgb::harness
