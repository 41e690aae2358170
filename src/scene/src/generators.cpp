// Generator parameters (defaults + scene file + knobs, validated) and dispatch.
#include <fgb/scene/generators.hpp>

#include "atrium.hpp"
#include "city.hpp"
#include "json_fields.hpp"
#include "small_generators.hpp"

#include <algorithm>
#include <charconv>

namespace fgb::scene {
namespace {

using nlohmann::json;

bool isAtriumBased(const std::string& type) {
  return type == "atrium" || type == "stress-far" || type == "stress-depth" || type == "stress-lights";
}

json withExtra(json params, const char* key, json value) {
  params[key] = std::move(value);
  return params;
}

json defaultsFor(const std::string& type) {
  const json atrium = {{"scale", 1.0}, {"seed", 1}, {"texture_size", 512}};
  if (type == "atrium" || type == "stress-depth") return atrium;
  if (type == "stress-far") return withExtra(atrium, "offset", 1e6);
  if (type == "stress-lights") return withExtra(atrium, "count", 64);
  if (type == "showcase") {
    return {{"objects", 9}, {"alpha", "opaque"}, {"floor", true}, {"lights", 4},
            {"emissive", false}, {"sun", true}, {"seed", 1}};
  }
  if (type == "stress-triangles") return {{"count", 2000}, {"seed", 1}};
  if (type == "stress-nan") return {{"fraction", 0.01}, {"seed", 1}};
  if (type == "city") return {{"blocks", 9}, {"seed", 1}, {"texture_size", 512}};
  return nullptr;
}

// Knob values arrive parsed (Knobs); store them as JSON numbers/booleans so params stay canonical
// (an integral number as an integer: part of the cooked cache key).
json knobValue(const KnobValue& value) {
  if (const auto* flag = std::get_if<bool>(&value)) return *flag;
  if (const auto* text = std::get_if<std::string>(&value)) return *text;
  if (const auto* vec = std::get_if<KnobVec3>(&value)) return json::array({(*vec)[0], (*vec)[1], (*vec)[2]});
  const double number = std::get<double>(value);
  if (number == double(int64_t(number)) && std::abs(number) < 9e15) return int64_t(number);
  return number;
}

void applyKnobs(json& params, const std::string& type, const Knobs& knobs) {
  std::vector<std::pair<std::string, KnobValue>> applicable;
  if (isAtriumBased(type)) {
    for (const auto& kv : knobs.withPrefix("atrium.")) applicable.push_back(kv);
  }
  if (type == "city") {
    for (const auto& kv : knobs.withPrefix("city.")) applicable.push_back(kv);
  }
  if (type.starts_with("stress-")) {
    for (const auto& kv : knobs.withPrefix("stress.")) {
      if (params.contains(kv.first)) applicable.push_back(kv);  // e.g. stress.offset only for stress-far
    }
  }
  for (const auto& [key, value] : applicable) params[key] = knobValue(value);
}

void validate(const json& params, const std::string& type, const detail::Fields& f) {
  const auto field = [](const std::string& key) { return "generator." + key; };
  for (const auto& item : params.items()) {
    const std::string& key = item.key();
    const json& v = item.value();
    if (key == "scale") {
      if (f.positive(v, field(key)) > 1000.0f) f.fail(field(key), "a density multiplier in (0, 1000]", &v);
    } else if (key == "seed" || key == "objects" || key == "lights" || key == "count") {
      if (f.count(v, field(key)) > 1000000u) f.fail(field(key), "an integer <= 1000000", &v);
    } else if (key == "blocks") {
      const uint32_t blocks = f.count(v, field(key));
      if (blocks < 2 || blocks > 64) f.fail(field(key), "an integer in [2, 64]", &v);
    } else if (key == "texture_size") {
      const uint32_t size = f.count(v, field(key));
      if (size < 4 || size > 4096 || (size & (size - 1)) != 0) f.fail(field(key), "a power of two in [4, 4096]", &v);
    } else if (key == "offset") {
      f.number(v, field(key));
    } else if (key == "fraction") {
      const double fraction = f.number(v, field(key));
      if (fraction < 0.0 || fraction > 1.0) f.fail(field(key), "a fraction in [0, 1]", &v);
    } else if (key == "alpha") {
      const std::string mode = f.string(v, field(key));
      if (mode != "opaque" && mode != "mask" && mode != "blend") f.fail(field(key), "\"opaque\", \"mask\" or \"blend\"", &v);
    } else if (key == "floor" || key == "emissive" || key == "sun") {
      f.boolean(v, field(key));
    }
  }
  (void)type;
}

AtriumParams atriumParams(const json& p) {
  AtriumParams a;
  a.scale = p.at("scale").get<double>();
  a.seed = p.at("seed").get<uint32_t>();
  a.textureSize = p.at("texture_size").get<uint32_t>();
  return a;
}

AlphaMode alphaMode(const std::string& text) {
  if (text == "mask") return AlphaMode::Mask;
  if (text == "blend") return AlphaMode::Blend;
  return AlphaMode::Opaque;
}

}  // namespace

const std::vector<std::string>& generatorNames() {
  static const std::vector<std::string> names = {"atrium",       "city",          "showcase",         "stress-far",
                                                 "stress-depth", "stress-lights", "stress-triangles", "stress-nan"};
  return names;
}

json resolveGeneratorParams(const GeneratorRef& generator, const Knobs& knobs, const std::string& where) {
  const detail::Fields f(where);
  json params = defaultsFor(generator.type);
  if (params.is_null()) {
    std::string list;
    for (const std::string& name : generatorNames()) list += (list.empty() ? "" : ", ") + name;
    const json got = generator.type;
    f.fail("generator.type", "one of " + list, &got);
  }
  for (const auto& item : generator.params.items()) {
    if (!params.contains(item.key())) {
      std::string list;
      for (const auto& known : params.items()) list += (list.empty() ? "" : ", ") + known.key();
      throw InputError(where + ": field 'generator." + item.key() + "': unknown parameter for generator '" +
                       generator.type + "' (expected one of: " + list + ")");
    }
    params[item.key()] = item.value();
  }
  applyKnobs(params, generator.type, knobs);
  validate(params, generator.type, detail::Fields(where + " (after --set knobs)"));
  // Canonical numbers: "scale": 1 and "scale": 1.0 must give the same cache key.
  for (const char* key : {"scale", "offset", "fraction"}) {
    if (params.contains(key)) params[key] = params[key].get<double>();
  }
  return params;
}

Scene generate(const std::string& type, const json& p) {
  if (type == "atrium") return buildAtrium(atriumParams(p));
  if (type == "stress-far") return buildStressFar(atriumParams(p), p.at("offset").get<double>());
  if (type == "stress-depth") return buildStressDepth(atriumParams(p));
  if (type == "stress-lights") return buildStressLights(atriumParams(p), p.at("count").get<uint32_t>(), p.at("seed").get<uint32_t>());
  if (type == "stress-triangles") return buildStressTriangles(p.at("count").get<uint32_t>(), p.at("seed").get<uint32_t>());
  if (type == "stress-nan") return buildStressNan(p.at("fraction").get<double>(), p.at("seed").get<uint32_t>());
  if (type == "city") {
    CityParams c;
    c.blocks = p.at("blocks").get<uint32_t>();
    c.seed = p.at("seed").get<uint32_t>();
    c.textureSize = p.at("texture_size").get<uint32_t>();
    return buildCity(c);
  }
  if (type == "showcase") {
    ShowcaseParams s;
    s.objects = p.at("objects").get<uint32_t>();
    s.alpha = alphaMode(p.at("alpha").get<std::string>());
    s.floor = p.at("floor").get<bool>();
    s.lights = p.at("lights").get<uint32_t>();
    s.emissive = p.at("emissive").get<bool>();
    s.sun = p.at("sun").get<bool>();
    s.seed = p.at("seed").get<uint32_t>();
    return buildShowcase(s, "generator 'showcase'");
  }
  throw InputError("unknown generator '" + type + "'");
}

}  // namespace fgb::scene
