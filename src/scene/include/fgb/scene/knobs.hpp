// `--set key=value` knobs. The scene side owns the prefixes atrium., stress., camera., scene. and
// post.; it rejects unknown keys under those prefixes and values out of range (InputError naming the
// key) and ignores every other key, which belongs to the renderer or harness. The CLI checks every
// key of every layer against one registry (fgb/core/knob_registry.hpp); knobSpecs() is this layer's part.
//
// Keys: atrium.scale (geometry density multiplier, > 0), atrium.seed, atrium.texture_size,
//       stress.offset (distance from the origin for stress-far), stress.seed,
//       camera.fov (vertical, degrees), camera.near, camera.far (a number or inf: infinite far
//       plane), camera.position (x,y,z), camera.target (x,y,z), post.exposure (a number or auto),
//       post.bloom (0|1), post.bloom_threshold, post.bloom_knee, post.bloom_intensity,
//       post.bloom_radius, scene.lights (0 drops point lights), scene.particles (0 drops
//       emitters), scene.sun (0|1), scene.light_scale (factor on every light, emissive and
//       particle radiance, the background and the bloom threshold), scene.emissive_scale (factor
//       on emissive materials and particles only), scene.offset=D (the whole scene and camera
//       moved by (D, 0, D) metres, any scene: the `offset` stress ladder).
#pragma once

#include <fgb/core/knob_registry.hpp>
#include <fgb/scene/scene.hpp>

#include <glm/ext/vector_double3.hpp>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::scene {

// The scene layer's entries of the knob registry (keys above, with types and ranges), from the
// table in knobs.cpp, where each knob's line also says where its value lands.
std::vector<KnobSpec> knobSpecs();

class Knobs;
// Applies the knobs that land in the loaded scene (camera, post, lights, offset; not the generator
// parameters atrium.* / stress.*), in the table's order, then checks the camera they leave
// (InputError: fov in (0, 179), 0 < near < far, target != position).
void applyKnobs(Scene& scene, const Knobs& knobs);

class Knobs {
 public:
  Knobs() = default;
  // The owned keys of `knobs`, each value checked and converted once (parseKnobValue, against
  // knobSpecs()): InputError naming the key for an unknown owned key or a bad value. Other keys
  // belong to other layers and are left out.
  static Knobs from(const std::map<std::string, std::string>& knobs);
  // The same from "key=value" strings (InputError when one has no '=').
  static Knobs parse(const std::vector<std::string>& assignments);

  static bool ownedByScene(std::string_view key);
  static const std::vector<std::string>& knownKeys();

  bool has(const std::string& key) const { return values_.count(key) != 0; }
  std::optional<KnobValue> value(const std::string& key) const {
    const auto it = values_.find(key);
    return it == values_.end() ? std::nullopt : std::optional<KnobValue>(it->second);
  }
  // Typed getters of the values parsed at construction: nullopt when unset (or, for number, set to
  // a word).
  std::optional<double> number(const std::string& key) const;
  // A number, or nullopt when unset or set to `word` (camera.far=inf, post.exposure=auto).
  std::optional<double> numberOr(const std::string& key, const std::string& word) const;
  bool isWord(const std::string& key, const std::string& word) const;
  // A positive factor in [1e-12, 1e12] (scene.light_scale, scene.emissive_scale).
  std::optional<double> scale(const std::string& key) const;
  std::optional<bool> flag(const std::string& key) const;
  std::optional<glm::dvec3> vec3(const std::string& key) const;  // double: camera positions far out

  // Owned knobs with a given prefix ("atrium."), without the prefix.
  std::map<std::string, KnobValue> withPrefix(const std::string& prefix) const;

 private:
  std::map<std::string, KnobValue> values_;  // owned keys only, parsed
};

}  // namespace fgb::scene
