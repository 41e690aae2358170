// Scene-owned --set knobs.
#include <fgb/scene/knobs.hpp>

#include <fgb/core/error.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace fgb::scene {
namespace {

const std::vector<std::string> kOwnedPrefixes = {"atrium.", "stress.", "camera.", "scene.", "post."};

std::string describe(const std::string& key, const std::string& value) { return "--set " + key + "=" + value; }

std::optional<double> parseNumber(std::string_view text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

const std::vector<std::string>& Knobs::knownKeys() {
  static const std::vector<std::string> keys = {
      "atrium.scale",       "atrium.seed",          "atrium.texture_size", "stress.offset",  "stress.seed",
      "camera.fov",         "camera.near",          "camera.far",          "camera.position", "camera.target",
      "post.exposure",      "post.bloom",           "post.bloom_threshold", "post.bloom_knee",
      "post.bloom_intensity", "post.bloom_radius",  "scene.lights",        "scene.particles", "scene.sun",
      "scene.light_scale",  "scene.emissive_scale", "scene.offset"};
  return keys;
}

bool Knobs::ownedByScene(std::string_view key) {
  return std::any_of(kOwnedPrefixes.begin(), kOwnedPrefixes.end(),
                     [&](const std::string& prefix) { return key.starts_with(prefix); });
}

Knobs Knobs::parse(const std::vector<std::string>& assignments) {
  Knobs knobs;
  for (const std::string& assignment : assignments) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) {
      throw InputError("--set " + assignment + ": expected key=value");
    }
    std::string key = assignment.substr(0, equals);
    if (!ownedByScene(key)) continue;
    const auto& known = knownKeys();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError("--set " + assignment + ": unknown scene knob '" + key + "' (known: " + list + ")");
    }
    knobs.values_[key] = assignment.substr(equals + 1);
  }
  // Parse every value now, so a malformed one fails before any work starts.
  for (const auto& [key, value] : knobs.values_) {
    if (key == "camera.position" || key == "camera.target") {
      (void)knobs.vec3(key);
    } else if (key == "camera.far" || key == "post.exposure") {
      (void)knobs.numberOr(key, key == "camera.far" ? "inf" : "auto");
    } else if (key == "scene.light_scale" || key == "scene.emissive_scale") {
      (void)knobs.scale(key);
    } else if (key == "scene.offset") {
      (void)knobs.number(key);
    } else if (key == "post.bloom" || key.starts_with("scene.")) {
      (void)knobs.flag(key);
    } else {
      (void)knobs.number(key);
    }
  }
  return knobs;
}

std::optional<double> Knobs::number(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return std::nullopt;
  const auto value = parseNumber(it->second);
  if (!value) throw InputError(describe(key, it->second) + ": expected a finite number");
  return value;
}

std::optional<double> Knobs::numberOr(const std::string& key, const std::string& word) const {
  const auto it = values_.find(key);
  if (it == values_.end() || it->second == word) return std::nullopt;
  const auto value = parseNumber(it->second);
  if (!value) throw InputError(describe(key, it->second) + ": expected a finite number or '" + word + "'");
  return value;
}

bool Knobs::isWord(const std::string& key, const std::string& word) const {
  const auto it = values_.find(key);
  return it != values_.end() && it->second == word;
}

std::optional<double> Knobs::scale(const std::string& key) const {
  const auto value = number(key);
  if (value && !(*value >= 1e-12 && *value <= 1e12)) {
    throw InputError(describe(key, values_.at(key)) + ": expected a factor in [1e-12, 1e12]");
  }
  return value;
}

std::optional<bool> Knobs::flag(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return std::nullopt;
  const std::string& v = it->second;
  if (v == "1" || v == "true" || v == "on") return true;
  if (v == "0" || v == "false" || v == "off") return false;
  throw InputError(describe(key, v) + ": expected 0|1|true|false|on|off");
}

std::optional<glm::dvec3> Knobs::vec3(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) return std::nullopt;
  glm::dvec3 result(0.0);
  std::string_view rest = it->second;
  for (int axis = 0; axis < 3; ++axis) {
    const size_t comma = rest.find(',');
    const auto component = parseNumber(rest.substr(0, comma));
    if (!component || (axis < 2) != (comma != std::string_view::npos)) {
      throw InputError(describe(key, it->second) + ": expected three numbers x,y,z");
    }
    result[axis] = *component;
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
  }
  return result;
}

std::map<std::string, std::string> Knobs::withPrefix(const std::string& prefix) const {
  std::map<std::string, std::string> result;
  for (const auto& [key, value] : values_) {
    if (key.starts_with(prefix)) result[key.substr(prefix.size())] = value;
  }
  return result;
}

}  // namespace fgb::scene
