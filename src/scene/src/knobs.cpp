// Scene-owned --set knobs.
#include <fgb/scene/knobs.hpp>

#include <fgb/core/error.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

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

KnobSpec number(std::string key, double min, double max, bool minExclusive, std::string help) {
  return {std::move(key),  KnobType::Number,     min, max, minExclusive, false, {}, "scene",
          std::move(help), ReferenceRole::Unset, {}};
}
KnobSpec integer(std::string key, double min, double max, std::string help) {
  return {std::move(key),  KnobType::Integer,    min, max, false, false, {}, "scene",
          std::move(help), ReferenceRole::Unset, {}};
}
KnobSpec typed(std::string key, KnobType type, std::string help) {
  KnobSpec spec;
  spec.key = std::move(key);
  spec.type = type;
  spec.owner = "scene";
  spec.help = std::move(help);
  return spec;
}

KnobSpec withWords(KnobSpec spec, std::vector<std::string> words) {
  spec.words = std::move(words);
  return spec;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

const KnobRegistry& sceneRegistry() {
  static const KnobRegistry registry = [] {
    KnobRegistry r;
    r.add(knobSpecs());
    return r;
  }();
  return registry;
}

}  // namespace

std::vector<KnobSpec> knobSpecs() {
  using enum ReferenceRole;
  KnobSpec fov = number("camera.fov", 0.0, 179.0, true, "vertical field of view, degrees");
  fov.maxExclusive = true;
  // What is drawn and from where: each value its own reference.
  std::vector<KnobSpec> content = {
      number("atrium.scale", 0.0, 1000.0, true, "geometry density multiplier"),
      integer("atrium.seed", 0, 1000000, "atrium layout seed"),
      integer("atrium.texture_size", 4, 4096, "procedural texture size (a power of two)"),
      number("stress.offset", -kInf, kInf, false, "stress-far: distance of the scene from the origin, m"),
      integer("stress.seed", 0, 1000000, "stress scenes' seed"),
      fov,
      number("camera.near", 0.0, kInf, true, "near plane, m"),
      withWords(number("camera.far", 0.0, kInf, true, "far plane, m (inf: infinite, reversed-Z)"), {"inf"}),
      typed("camera.position", KnobType::Vec3, "camera position x,y,z"),
      typed("camera.target", KnobType::Vec3, "camera target x,y,z"),
      typed("scene.lights", KnobType::Flag, "0 drops the point lights"),
      typed("scene.particles", KnobType::Flag, "0 drops the particle emitters"),
      typed("scene.sun", KnobType::Flag, "sun on/off"),
      number("scene.light_scale", 1e-12, 1e12, false, "factor on every light, emissive, particle, background"),
      number("scene.emissive_scale", 1e-12, 1e12, false, "factor on emissive materials and particles"),
      number("scene.offset", -1e9, 1e9, false, "whole scene and camera moved by (d, 0, d) m"),
  };
  // The intended image's post-processing: copied, and judged against the scene's own when varied.
  std::vector<KnobSpec> look = {
      withWords(number("post.exposure", 0.0, kInf, true, "tone-mapping exposure (auto: metered)"), {"auto"}),
      typed("post.bloom", KnobType::Flag, "bloom on/off"),
      number("post.bloom_threshold", 0.0, kInf, false, "bloom threshold"),
      number("post.bloom_knee", 0.0, kInf, false, "bloom soft knee"),
      number("post.bloom_intensity", 0.0, kInf, false, "bloom intensity"),
      number("post.bloom_radius", 0.0, kInf, true, "bloom upsample radius"),
  };
  std::vector<KnobSpec> specs;
  for (KnobSpec& spec : content) specs.push_back(withRole(std::move(spec), Content));
  for (KnobSpec& spec : look) specs.push_back(withRole(std::move(spec), Look));
  return specs;
}

const std::vector<std::string>& Knobs::knownKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> list;
    for (const KnobSpec& spec : knobSpecs()) list.push_back(spec.key);
    return list;
  }();
  return keys;
}

bool Knobs::ownedByScene(std::string_view key) {
  return std::any_of(kOwnedPrefixes.begin(), kOwnedPrefixes.end(),
                     [&](const std::string& prefix) { return key.starts_with(prefix); });
}

Knobs Knobs::parse(const std::vector<std::string>& assignments) {
  Knobs knobs;
  // Every value is checked now (type and range, from knobSpecs()), so a bad one fails before any
  // work starts; keys outside the scene's prefixes belong to other layers and are left to them.
  for (const auto& [key, value] : splitKnobAssignments(assignments)) {
    if (!ownedByScene(key)) continue;
    sceneRegistry().check(key, value);
    knobs.values_[key] = value;
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
