// Scene file parsing and validation.
#include <fgb/scene/scene_file.hpp>

#include <fgb/scene/camera_path.hpp>

#include "json_fields.hpp"

#include <glm/ext/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace fgb::scene {
namespace {

using detail::Fields;
using nlohmann::json;

// Top-level sections read by other components; the scene side passes them through untouched.
constexpr std::initializer_list<const char*> kTopLevelKeys = {
    "name", "description", "model", "models", "generator", "camera", "lights", "sun", "emitters", "post",
    "render", "renderer", "budget", "golden", "harness", "tags"};

bool isPassThrough(const std::string& key) {
  return key == "render" || key == "renderer" || key == "budget" || key == "golden" || key == "harness" ||
         key == "tags";
}

glm::dmat4 parsePlacement(const Fields& f, const json& model, const std::string& field) {
  glm::dmat4 placement(1.0);
  if (model.contains("position")) placement = glm::translate(placement, f.dvec3(model["position"], field + ".position"));
  if (model.contains("rotation_deg")) {
    const glm::vec3 degrees = f.vec3(model["rotation_deg"], field + ".rotation_deg");
    // Applied Y (yaw), then X (pitch), then Z (roll), all in the model's parent frame.
    const glm::dvec3 radians = glm::radians(glm::dvec3(degrees));
    placement = glm::rotate(placement, radians.y, glm::dvec3(0, 1, 0));
    placement = glm::rotate(placement, radians.x, glm::dvec3(1, 0, 0));
    placement = glm::rotate(placement, radians.z, glm::dvec3(0, 0, 1));
  }
  if (model.contains("scale")) {
    const json& scale = model["scale"];
    const glm::vec3 factors = scale.is_array() ? f.vec3(scale, field + ".scale")
                                               : glm::vec3(f.positive(scale, field + ".scale"));
    if (!(factors.x > 0 && factors.y > 0 && factors.z > 0)) f.fail(field + ".scale", "positive factors", &scale);
    placement = glm::scale(placement, glm::dvec3(factors));
  }
  return placement;
}

ModelRef parseModel(const Fields& f, const json& value, const std::string& field, const std::filesystem::path& base) {
  ModelRef ref;
  ref.field = field;
  if (value.is_string()) {
    ref.file = base / value.get<std::string>();
    return ref;
  }
  f.object(value, field);
  f.onlyKeys(value, field, {"file", "position", "rotation_deg", "scale"});
  if (!value.contains("file")) f.fail(field + ".file", "a model path", nullptr);
  ref.file = base / f.string(value["file"], field + ".file");
  ref.placement = parsePlacement(f, value, field);
  return ref;
}

PointLight parseLight(const Fields& f, const json& value, const std::string& field) {
  f.object(value, field);
  f.onlyKeys(value, field, {"position", "color", "intensity", "radius"});
  PointLight light;
  if (!value.contains("position")) f.fail(field + ".position", "an array of 3 numbers", nullptr);
  light.position = f.dvec3(value["position"], field + ".position");
  if (value.contains("color")) light.color = f.vec3(value["color"], field + ".color");
  if (value.contains("intensity")) light.intensity = f.nonNegative(value["intensity"], field + ".intensity");
  if (value.contains("radius")) light.radius = f.positive(value["radius"], field + ".radius");
  return light;
}

DirectionalLight parseSun(const Fields& f, const json& value, const std::string& field) {
  f.object(value, field);
  f.onlyKeys(value, field, {"direction", "color", "intensity", "enabled"});
  DirectionalLight sun;
  sun.enabled = value.contains("enabled") ? f.boolean(value["enabled"], field + ".enabled") : true;
  sun.intensity = 3.0f;
  if (value.contains("direction")) {
    const glm::vec3 d = f.vec3(value["direction"], field + ".direction");
    if (glm::length(d) <= 0.0f) f.fail(field + ".direction", "a non-zero vector", &value["direction"]);
    sun.direction = glm::normalize(d);
  }
  if (value.contains("color")) sun.color = f.vec3(value["color"], field + ".color");
  if (value.contains("intensity")) sun.intensity = f.nonNegative(value["intensity"], field + ".intensity");
  return sun;
}

Emitter parseEmitter(const Fields& f, const json& value, const std::string& field) {
  f.object(value, field);
  f.onlyKeys(value, field, {"name", "position", "rate", "lifetime", "direction", "cone_deg", "speed", "color_start",
                            "color_end", "size_start", "size_end", "max_particles", "seed"});
  Emitter e;
  e.name = value.contains("name") ? f.string(value["name"], field + ".name") : field;
  if (!value.contains("position")) f.fail(field + ".position", "an array of 3 numbers", nullptr);
  e.position = f.dvec3(value["position"], field + ".position");
  if (value.contains("rate")) e.rate = f.nonNegative(value["rate"], field + ".rate");
  if (value.contains("lifetime")) e.lifetime = f.positive(value["lifetime"], field + ".lifetime");
  if (value.contains("direction")) {
    const glm::vec3 d = f.vec3(value["direction"], field + ".direction");
    if (glm::length(d) <= 0.0f) f.fail(field + ".direction", "a non-zero vector", &value["direction"]);
    e.direction = glm::normalize(d);
  }
  if (value.contains("cone_deg")) e.coneAngleDeg = f.nonNegative(value["cone_deg"], field + ".cone_deg");
  if (value.contains("speed")) {
    const json& speed = value["speed"];
    if (!speed.is_array() || speed.size() != 2) f.fail(field + ".speed", "[min, max]", &speed);
    e.speedMin = f.nonNegative(speed[0], field + ".speed[0]");
    e.speedMax = f.nonNegative(speed[1], field + ".speed[1]");
    if (e.speedMax < e.speedMin) f.fail(field + ".speed", "[min, max] with min <= max", &speed);
  }
  if (value.contains("color_start")) e.colorStart = f.vec4(value["color_start"], field + ".color_start");
  if (value.contains("color_end")) e.colorEnd = f.vec4(value["color_end"], field + ".color_end");
  if (value.contains("size_start")) e.sizeStart = f.nonNegative(value["size_start"], field + ".size_start");
  if (value.contains("size_end")) e.sizeEnd = f.nonNegative(value["size_end"], field + ".size_end");
  if (value.contains("max_particles")) e.maxParticles = f.count(value["max_particles"], field + ".max_particles");
  if (value.contains("seed")) e.seed = f.count(value["seed"], field + ".seed");
  return e;
}

template <typename Parse>
auto parseArray(const Fields& f, const json& value, const std::string& field, Parse&& parseOne) {
  if (!value.is_array()) f.fail(field, "an array", &value);
  std::vector<decltype(parseOne(value, field))> items;
  for (size_t i = 0; i < value.size(); ++i) items.push_back(parseOne(value[i], field + "[" + std::to_string(i) + "]"));
  return items;
}

GeneratorRef parseGenerator(const Fields& f, const json& value) {
  GeneratorRef ref;
  if (value.is_string()) {
    ref.type = value.get<std::string>();
    ref.params = json::object();
    return ref;
  }
  f.object(value, "generator");
  if (!value.contains("type")) f.fail("generator.type", "a generator name (atrium, city, showcase, stress-*)", nullptr);
  ref.type = f.string(value["type"], "generator.type");
  ref.params = value;
  ref.params.erase("type");
  return ref;
}

}  // namespace

void applyCameraOverrides(Camera& camera, const json& overrides, const std::string& where) {
  if (overrides.is_null()) return;
  const Fields f(where);
  f.object(overrides, "camera");
  f.onlyKeys(overrides, "camera", {"position", "target", "up", "fov_deg", "near", "far", "path"});  // path: parseCameraPath
  if (overrides.contains("position")) camera.position = f.dvec3(overrides["position"], "camera.position");
  if (overrides.contains("target")) camera.target = f.dvec3(overrides["target"], "camera.target");
  if (overrides.contains("up")) camera.up = f.vec3(overrides["up"], "camera.up");
  if (overrides.contains("fov_deg")) {
    camera.verticalFovDeg = f.positive(overrides["fov_deg"], "camera.fov_deg");
    if (camera.verticalFovDeg >= 179.0f) f.fail("camera.fov_deg", "degrees in (0, 179)", &overrides["fov_deg"]);
  }
  if (overrides.contains("near")) camera.nearPlane = f.positive(overrides["near"], "camera.near");
  if (overrides.contains("far")) {
    const json& far = overrides["far"];  // a number, or "inf": an infinite far plane (reversed-Z)
    camera.farPlane = far == "inf" ? std::numeric_limits<float>::infinity() : f.positive(far, "camera.far");
  }
  if (camera.farPlane <= camera.nearPlane) f.fail("camera.far", "a value greater than camera.near", nullptr);
  if (glm::length(camera.target - camera.position) <= 0.0f) {
    f.fail("camera.target", "a point different from camera.position", nullptr);
  }
}

void applyPostOverrides(PostSettings& post, const json& overrides, const std::string& where) {
  if (overrides.is_null()) return;
  const Fields f(where);
  f.object(overrides, "post");
  f.onlyKeys(overrides, "post", {"exposure", "bloom"});
  if (overrides.contains("exposure")) {
    const json& exposure = overrides["exposure"];
    post.autoExposure = exposure == "auto";
    if (!post.autoExposure) post.exposure = f.positive(exposure, "post.exposure");
  }
  if (!overrides.contains("bloom")) return;
  const json& bloom = overrides["bloom"];
  if (bloom.is_boolean()) {
    post.bloom.enabled = bloom.get<bool>();
    return;
  }
  f.object(bloom, "post.bloom");
  f.onlyKeys(bloom, "post.bloom", {"enabled", "threshold", "knee", "intensity", "radius"});
  if (bloom.contains("enabled")) post.bloom.enabled = f.boolean(bloom["enabled"], "post.bloom.enabled");
  if (bloom.contains("threshold")) post.bloom.threshold = f.nonNegative(bloom["threshold"], "post.bloom.threshold");
  if (bloom.contains("knee")) post.bloom.knee = f.nonNegative(bloom["knee"], "post.bloom.knee");
  if (bloom.contains("intensity")) post.bloom.intensity = f.nonNegative(bloom["intensity"], "post.bloom.intensity");
  if (bloom.contains("radius")) post.bloom.radius = f.positive(bloom["radius"], "post.bloom.radius");
}

SceneDescription parseSceneText(const std::string& text, const std::filesystem::path& path) {
  const Fields f(path.string());
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's message names the byte offset; keep it on one line.
    throw InputError(path.string() + ": not valid JSON: " + std::string(e.what()));
  }
  f.object(root, "(top level)");
  for (const auto& item : root.items()) {
    const bool known = std::any_of(kTopLevelKeys.begin(), kTopLevelKeys.end(),
                                   [&](const char* key) { return item.key() == key; });
    if (!known && !item.key().starts_with("x-") && !item.key().starts_with("_")) f.onlyKeys(root, "", kTopLevelKeys);
  }

  SceneDescription d;
  d.path = path;
  const std::filesystem::path base = path.parent_path();
  d.name = root.contains("name") ? f.string(root["name"], "name") : path.stem().string();
  if (root.contains("generator")) d.generator = parseGenerator(f, root["generator"]);
  if (root.contains("model")) d.models.push_back(parseModel(f, root["model"], "model", base));
  if (root.contains("models")) {
    d.models = parseArray(f, root["models"], "models",
                          [&](const json& v, const std::string& field) { return parseModel(f, v, field, base); });
  }
  if (root.contains("model") && root.contains("models")) f.fail("models", "either 'model' or 'models', not both", nullptr);
  if (root.contains("lights")) {
    d.lights = parseArray(f, root["lights"], "lights",
                          [&](const json& v, const std::string& field) { return parseLight(f, v, field); });
  }
  if (root.contains("sun")) d.sun = parseSun(f, root["sun"], "sun");
  if (root.contains("emitters")) {
    d.emitters = parseArray(f, root["emitters"], "emitters",
                            [&](const json& v, const std::string& field) { return parseEmitter(f, v, field); });
  }
  if (root.contains("camera")) {
    d.camera = root["camera"];
    Camera probe;  // validate now so a bad camera fails before any loading
    applyCameraOverrides(probe, d.camera, path.string());
    if (d.camera.contains("path")) parseCameraPath(d.camera["path"], path.string());
  }
  if (root.contains("post")) {
    d.post = root["post"];
    PostSettings probe;
    applyPostOverrides(probe, d.post, path.string());
  }
  d.renderer = json::object();
  for (const auto& item : root.items()) {
    if (isPassThrough(item.key())) d.renderer[item.key()] = item.value();
  }
  return d;
}

SceneDescription parseSceneFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path.string() + ": is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseSceneText(text.str(), path);
}

}  // namespace fgb::scene
