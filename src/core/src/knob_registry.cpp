#include <algorithm>
#include <charconv>
#include <cmath>
#include <fgb/core/error.hpp>
#include <fgb/core/knob_registry.hpp>
#include <stdexcept>
#include <utility>

namespace fgb {
namespace {

bool isWordOf(const KnobSpec& spec, std::string_view value) {
  return std::find(spec.words.begin(), spec.words.end(), value) != spec.words.end();
}

bool parseDouble(std::string_view text, double& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && ptr == end && std::isfinite(value);
}

bool parseInteger(std::string_view text, double& value) {
  long long parsed = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, parsed);
  value = double(parsed);
  return error == std::errc() && ptr == end;
}

bool inRange(const KnobSpec& spec, double value) {
  const bool aboveMin = spec.minExclusive ? value > spec.min : value >= spec.min;
  const bool belowMax = spec.maxExclusive ? value < spec.max : value <= spec.max;
  return aboveMin && belowMax;
}

std::optional<KnobVec3> parseVec3(std::string_view text) {
  KnobVec3 vec{};
  for (int axis = 0; axis < 3; ++axis) {
    const size_t comma = text.find(',');
    if ((axis < 2) != (comma != std::string_view::npos)) return std::nullopt;
    if (!parseDouble(text.substr(0, comma), vec[size_t(axis)])) return std::nullopt;
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
  }
  return vec;
}

std::string formatBound(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : std::to_string(value);
}

std::string joinWords(const std::vector<std::string>& words, const char* separator) {
  std::string joined;
  for (const std::string& word : words) joined += (joined.empty() ? "" : separator) + word;
  return joined;
}

std::string describeRange(const KnobSpec& spec, const char* noun) {
  const bool hasMin = std::isfinite(spec.min);
  const bool hasMax = std::isfinite(spec.max);
  std::string text = noun;
  if (hasMin && hasMax) {
    text += std::string(" in ") + (spec.minExclusive ? "(" : "[") + formatBound(spec.min) + ", " +
            formatBound(spec.max) + (spec.maxExclusive ? ")" : "]");
  } else if (hasMin) {
    text += (spec.minExclusive ? " > " : " >= ") + formatBound(spec.min);
  } else if (hasMax) {
    text += (spec.maxExclusive ? " < " : " <= ") + formatBound(spec.max);
  }
  if (!spec.words.empty()) text += " or " + joinWords(spec.words, "|");
  return text;
}

}  // namespace

std::string describeExpected(const KnobSpec& spec) {
  switch (spec.type) {
    case KnobType::Integer:
      return describeRange(spec, "an integer");
    case KnobType::Number:
      return describeRange(spec, "a finite number");
    case KnobType::Flag:
      return "0|1|true|false|on|off";
    case KnobType::Word:
      return joinWords(spec.words, "|");
    case KnobType::Vec3:
      return "three numbers x,y,z";
    case KnobType::Text:
      return "a non-empty value";
    case KnobType::WordOrFile:
      return joinWords(spec.words, "|") + " or FILE.json";
  }
  return "a value";
}

std::optional<KnobValue> tryParseKnobValue(const KnobSpec& spec, std::string_view value) {
  double number = 0.0;
  switch (spec.type) {
    case KnobType::Integer:
      if (isWordOf(spec, value)) return std::string(value);
      if (parseInteger(value, number) && inRange(spec, number)) return number;
      return std::nullopt;
    case KnobType::Number:
      if (isWordOf(spec, value)) return std::string(value);
      if (parseDouble(value, number) && inRange(spec, number)) return number;
      return std::nullopt;
    case KnobType::Flag:
      if (value == "1" || value == "true" || value == "on") return true;
      if (value == "0" || value == "false" || value == "off") return false;
      return std::nullopt;
    case KnobType::Word:
      if (isWordOf(spec, value)) return std::string(value);
      return std::nullopt;
    case KnobType::Vec3:
      if (const auto vec = parseVec3(value)) return *vec;
      return std::nullopt;
    case KnobType::Text:
      if (!value.empty()) return std::string(value);
      return std::nullopt;
    case KnobType::WordOrFile:
      if (isWordOf(spec, value) || (value.size() > 5 && value.ends_with(".json"))) return std::string(value);
      return std::nullopt;
  }
  return std::nullopt;
}

KnobValue parseKnobValue(const KnobSpec& spec, std::string_view value) {
  if (auto parsed = tryParseKnobValue(spec, value)) return std::move(*parsed);
  throw InputError("--set " + spec.key + "=" + std::string(value) + ": expected " + describeExpected(spec));
}

bool knobValueValid(const KnobSpec& spec, std::string_view value) { return tryParseKnobValue(spec, value).has_value(); }

KnobSpec withRole(KnobSpec spec, ReferenceRole role, std::string exact) {
  spec.role = role;
  spec.exact = std::move(exact);
  return spec;
}

const char* referenceRoleName(ReferenceRole role) {
  switch (role) {
    case ReferenceRole::Approximation:
      return "approximation";
    case ReferenceRole::Look:
      return "look";
    case ReferenceRole::Content:
      return "content";
    case ReferenceRole::CostOnly:
      return "cost-only";
    case ReferenceRole::Unset:
      break;
  }
  return "unset";
}

void KnobRegistry::add(const std::vector<KnobSpec>& specs) {
  for (const KnobSpec& spec : specs) {
    if (find(spec.key)) throw std::logic_error("knob '" + spec.key + "' registered twice");
    if (spec.role == ReferenceRole::Unset)
      throw std::logic_error("knob '" + spec.key + "' has no reference role (fgb/core/knob_registry.hpp)");
    if (spec.role == ReferenceRole::Approximation && !knobValueValid(spec, spec.exact))
      throw std::logic_error("knob '" + spec.key + "': its exact value '" + spec.exact + "' is out of its range");
    if (spec.role == ReferenceRole::CostOnly && !spec.exact.empty() && !knobValueValid(spec, spec.exact))
      throw std::logic_error("knob '" + spec.key + "': its pinned value '" + spec.exact + "' is out of its range");
    specs_.push_back(spec);
  }
  std::sort(specs_.begin(), specs_.end(), [](const KnobSpec& a, const KnobSpec& b) { return a.key < b.key; });
}

const KnobSpec* KnobRegistry::find(std::string_view key) const {
  const auto it = std::find_if(specs_.begin(), specs_.end(), [&](const KnobSpec& spec) { return spec.key == key; });
  return it == specs_.end() ? nullptr : &*it;
}

std::string KnobRegistry::knownKeys() const {
  std::string list;
  for (const KnobSpec& spec : specs_) list += (list.empty() ? "" : ", ") + spec.key;
  return list;
}

void KnobRegistry::check(const std::string& key, const std::string& value) const { (void)parse(key, value); }

KnobValue KnobRegistry::parse(const std::string& key, const std::string& value) const {
  const KnobSpec* spec = find(key);
  if (!spec)
    throw InputError("--set " + key + "=" + value + ": unknown knob '" + key + "' (known: " + knownKeys() + ")");
  return parseKnobValue(*spec, value);
}

void KnobRegistry::checkAll(const std::map<std::string, std::string>& knobs) const {
  for (const auto& [key, value] : knobs) check(key, value);
}

std::map<std::string, std::string> splitKnobAssignments(const std::vector<std::string>& assignments) {
  std::map<std::string, std::string> knobs;
  for (const std::string& assignment : assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) throw InputError("--set " + assignment + ": expected key=value");
    knobs[assignment.substr(0, equals)] = assignment.substr(equals + 1);
  }
  return knobs;
}

}  // namespace fgb
