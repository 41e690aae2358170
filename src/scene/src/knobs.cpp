// Scene-owned --set knobs.
#include <fgb/scene/knobs.hpp>

#include <fgb/core/error.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>

namespace fgb::scene {
namespace {

const std::vector<std::string> kOwnedPrefixes = {"atrium.", "city.", "stress.", "camera.", "scene.", "post."};

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

// Emissive materials and particles (whose colours are emitted radiance).
void scaleEmissive(Scene& scene, float factor) {
  for (Material& material : scene.materials) material.emissiveStrength *= factor;
  for (Emitter& emitter : scene.emitters) {
    emitter.colorStart = glm::vec4(glm::vec3(emitter.colorStart) * factor, emitter.colorStart.a);
    emitter.colorEnd = glm::vec4(glm::vec3(emitter.colorEnd) * factor, emitter.colorEnd.a);
  }
}

// Every source of radiance, and the bloom threshold (a radiance level): with the exposure divided
// by the same factor the image should not change (the `light-scale` stress ladder).
void scaleLights(Scene& scene, float factor) {
  for (PointLight& light : scene.lights) light.intensity *= factor;
  scene.sun.intensity *= factor;
  scaleEmissive(scene, factor);
  scene.post.lightScale *= factor;
  scene.post.bloom.threshold *= factor;
}

// The whole scene and its camera moved by `offset` (world placement is double: nothing is lost).
void translateScene(Scene& scene, const glm::dvec3& offset) {
  for (Instance& instance : scene.instances) {
    instance.transform[3] += glm::dvec4(offset, 0.0);
    if (!instance.worldBounds.isEmpty()) instance.worldBounds = {instance.worldBounds.min + offset, instance.worldBounds.max + offset};
  }
  for (PointLight& light : scene.lights) light.position += offset;
  for (Emitter& emitter : scene.emitters) emitter.position += offset;
  scene.camera.position += offset;
  scene.camera.target += offset;
  for (CameraKey& key : scene.cameraPath.keys()) {
    key.position += offset;
    key.target += offset;
  }
}

// camera.time=T: the renderer holds the view at the path's time T (Scene::stillTime), with the
// particles simulated up to T. The path stays: the still view is computed from it exactly as the
// path's frame at T is, and the particles keep their space (the still camera's).
void stillAt(Scene& scene, double time) { scene.stillTime = time; }

// camera.distance=F: the camera F times as far from its target (every path key too), the far plane
// moved with it unless infinite, so what lies behind the target stays inside it.
void scaleCameraDistance(Scene& scene, double factor) {
  const auto scaled = [factor](const glm::dvec3& position, const glm::dvec3& target) {
    return target + (position - target) * factor;
  };
  Camera& camera = scene.camera;
  camera.position = scaled(camera.position, camera.target);
  if (std::isfinite(camera.farPlane)) camera.farPlane = static_cast<float>(camera.farPlane * factor);
  for (CameraKey& key : scene.cameraPath.keys()) key.position = scaled(key.position, key.target);
}

// One scene knob, one line of the table below: its registry entry with its reference role, and
// where its value (parsed once) lands in the loaded scene; none for the generator parameters
// (atrium.*, city.*, stress.*: the parameter of the same name, generators.cpp).
struct SceneKnob {
  KnobSpec spec;
  std::function<void(Scene&, const KnobValue&)> land;
};
using Land = std::function<void(Scene&, const KnobValue&)>;
SceneKnob knob(KnobSpec spec, ReferenceRole role, Land land = {}) { return {withRole(std::move(spec), role), std::move(land)}; }
KnobSpec exclusiveMax(KnobSpec spec) {
  spec.maxExclusive = true;
  return spec;
}
double number(const KnobValue& v) { return std::get<double>(v); }
float single(const KnobValue& v) { return static_cast<float>(std::get<double>(v)); }
bool flag(const KnobValue& v) { return std::get<bool>(v); }
glm::dvec3 vec3(const KnobValue& v) {
  const KnobVec3& xyz = std::get<KnobVec3>(v);
  return {xyz[0], xyz[1], xyz[2]};
}

// In the order the values are applied: camera knobs describe the scene before it moves (the
// offset last: any offset gives the same image), the light scale scales the bloom threshold the
// post knobs set. Content: what is drawn and from where (each value its own reference); look: the
// intended image's post-processing (copied, and judged against the scene's own when varied).
const std::vector<SceneKnob>& sceneKnobs() {
  using enum ReferenceRole;
  static const std::vector<SceneKnob> knobs = {
      knob(number("atrium.scale", 0.0, 1000.0, true, "geometry density multiplier"), Content),
      knob(integer("atrium.seed", 0, 1000000, "atrium layout seed"), Content),
      knob(integer("atrium.texture_size", 4, 4096, "procedural texture size (a power of two)"), Content),
      knob(integer("city.blocks", 2, 64, "city blocks per side"), Content),
      knob(integer("city.seed", 0, 1000000, "city layout seed"), Content),
      knob(integer("city.texture_size", 4, 4096, "procedural texture size (a power of two)"), Content),
      knob(number("stress.offset", -kInf, kInf, false, "stress-far: distance of the scene from the origin, m"), Content),
      knob(integer("stress.seed", 0, 1000000, "stress scenes' seed"), Content),
      knob(exclusiveMax(number("camera.fov", 0.0, 179.0, true, "vertical field of view, degrees")), Content,
           [](Scene& s, const KnobValue& v) { s.camera.verticalFovDeg = single(v); }),
      knob(number("camera.near", 0.0, kInf, true, "near plane, m"), Content,
           [](Scene& s, const KnobValue& v) { s.camera.nearPlane = single(v); }),
      knob(withWords(number("camera.far", 0.0, kInf, true, "far plane, m (inf: infinite, reversed-Z)"), {"inf"}), Content,
           [](Scene& s, const KnobValue& v) {
             s.camera.farPlane = std::holds_alternative<double>(v) ? single(v) : std::numeric_limits<float>::infinity();
           }),
      knob(typed("camera.position", KnobType::Vec3, "camera position x,y,z"), Content,
           [](Scene& s, const KnobValue& v) { s.camera.position = vec3(v); }),
      knob(typed("camera.target", KnobType::Vec3, "camera target x,y,z"), Content,
           [](Scene& s, const KnobValue& v) { s.camera.target = vec3(v); }),
      knob(withWords(typed("camera.path", KnobType::Word, "none: the still view instead of the scene's path"), {"none"}),
           Content, [](Scene& s, const KnobValue&) { s.cameraPath = {}; }),
      knob(number("camera.time", 0.0, 1e6, false, "still view at this path time, s (particles simulated to it)"), Content,
           [](Scene& s, const KnobValue& v) { stillAt(s, number(v)); }),
      knob(number("camera.distance", 0.0, 1e6, true, "camera distance from its target times F (far plane too)"), Content,
           [](Scene& s, const KnobValue& v) { scaleCameraDistance(s, number(v)); }),
      knob(withWords(number("post.exposure", 0.0, kInf, true, "tone-mapping exposure (auto: metered)"), {"auto"}), Look,
           [](Scene& s, const KnobValue& v) {
             s.post.autoExposure = !std::holds_alternative<double>(v);
             if (!s.post.autoExposure) s.post.exposure = single(v);
           }),
      knob(typed("post.bloom", KnobType::Flag, "bloom on/off"), Look,
           [](Scene& s, const KnobValue& v) { s.post.bloom.enabled = flag(v); }),
      knob(number("post.bloom_threshold", 0.0, kInf, false, "bloom threshold"), Look,
           [](Scene& s, const KnobValue& v) { s.post.bloom.threshold = single(v); }),
      knob(number("post.bloom_knee", 0.0, kInf, false, "bloom soft knee"), Look,
           [](Scene& s, const KnobValue& v) { s.post.bloom.knee = single(v); }),
      knob(number("post.bloom_intensity", 0.0, kInf, false, "bloom intensity"), Look,
           [](Scene& s, const KnobValue& v) { s.post.bloom.intensity = single(v); }),
      knob(number("post.bloom_radius", 0.0, kInf, true, "bloom upsample radius"), Look,
           [](Scene& s, const KnobValue& v) { s.post.bloom.radius = single(v); }),
      knob(typed("scene.lights", KnobType::Flag, "0 drops the point lights"), Content,
           [](Scene& s, const KnobValue& v) { if (!flag(v)) s.lights.clear(); }),
      knob(typed("scene.particles", KnobType::Flag, "0 drops the particle emitters"), Content,
           [](Scene& s, const KnobValue& v) { if (!flag(v)) s.emitters.clear(); }),
      knob(typed("scene.sun", KnobType::Flag, "sun on/off"), Content,
           [](Scene& s, const KnobValue& v) { s.sun.enabled = flag(v); }),
      knob(number("scene.light_scale", 1e-12, 1e12, false, "factor on every light, emissive, particle, background"),
           Content, [](Scene& s, const KnobValue& v) { scaleLights(s, single(v)); }),
      knob(number("scene.emissive_scale", 1e-12, 1e12, false, "factor on emissive materials and particles"), Content,
           [](Scene& s, const KnobValue& v) { scaleEmissive(s, single(v)); }),
      knob(number("scene.offset", -1e9, 1e9, false, "whole scene and camera moved by (d, 0, d) m"), Content,
           [](Scene& s, const KnobValue& v) { translateScene(s, glm::dvec3(number(v), 0.0, number(v))); }),
  };
  return knobs;
}

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
  std::vector<KnobSpec> specs;
  for (const SceneKnob& knob : sceneKnobs()) specs.push_back(knob.spec);
  return specs;
}

void applyKnobs(Scene& scene, const Knobs& knobs) {
  for (const SceneKnob& knob : sceneKnobs()) {
    if (!knob.land) continue;
    if (const auto value = knobs.value(knob.spec.key)) knob.land(scene, *value);
  }
  const Camera& c = scene.camera;
  if (!(c.verticalFovDeg > 0.0f && c.verticalFovDeg < 179.0f)) throw InputError("--set camera.fov: expected degrees in (0, 179)");
  if (!(c.nearPlane > 0.0f && c.farPlane > c.nearPlane)) throw InputError("--set camera.near/far: expected 0 < near < far");
  if (glm::length(c.target - c.position) <= 0.0f) throw InputError("--set camera.target: must differ from the position");
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

Knobs Knobs::from(const std::map<std::string, std::string>& values) {
  Knobs knobs;
  // Every value is checked and converted now (type and range, from knobSpecs()), so a bad one fails
  // before any work starts; keys outside the scene's prefixes belong to other layers.
  for (const auto& [key, value] : values) {
    if (!ownedByScene(key)) continue;
    knobs.values_[key] = sceneRegistry().parse(key, value);
  }
  return knobs;
}

Knobs Knobs::parse(const std::vector<std::string>& assignments) { return from(splitKnobAssignments(assignments)); }

std::optional<double> Knobs::number(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end() || !std::holds_alternative<double>(it->second)) return std::nullopt;
  return std::get<double>(it->second);
}

std::optional<double> Knobs::numberOr(const std::string& key, const std::string& /*word*/) const { return number(key); }

bool Knobs::isWord(const std::string& key, const std::string& word) const {
  const auto it = values_.find(key);
  return it != values_.end() && std::holds_alternative<std::string>(it->second) &&
         std::get<std::string>(it->second) == word;
}

// The registry's range is the factor's range (knobSpecs()).
std::optional<double> Knobs::scale(const std::string& key) const { return number(key); }

std::optional<bool> Knobs::flag(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end() || !std::holds_alternative<bool>(it->second)) return std::nullopt;
  return std::get<bool>(it->second);
}

std::optional<glm::dvec3> Knobs::vec3(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end() || !std::holds_alternative<KnobVec3>(it->second)) return std::nullopt;
  const KnobVec3& v = std::get<KnobVec3>(it->second);
  return glm::dvec3(v[0], v[1], v[2]);
}

std::map<std::string, KnobValue> Knobs::withPrefix(const std::string& prefix) const {
  std::map<std::string, KnobValue> result;
  for (const auto& [key, value] : values_) {
    if (key.starts_with(prefix)) result[key.substr(prefix.size())] = value;
  }
  return result;
}

}  // namespace fgb::scene
