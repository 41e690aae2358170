#include "render_paths.hpp"

#include <fgb/core/error.hpp>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "../features/feature_registry.hpp"
#include "../features/tonemap/tonemap_feature.hpp"

namespace fgb::render {
namespace {

using nlohmann::json;
using features::FeatureKind;
using features::RenderPath;

// One line: "--set render.path=SOURCE: WHAT".
[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw InputError("--set render.path=" + source + ": " + what);
}

std::string quoted(const std::string& text) { return "\"" + text + "\""; }

std::string joined(const std::vector<std::string>& words) {
  std::string list;
  for (const std::string& word : words) list += (list.empty() ? "" : ", ") + word;
  return list;
}

// Refuses a key of `object` outside `known`; `where` names the object ("", "features[2]: ", ...).
void checkKeys(const std::string& source, const std::string& where, const json& object,
               const std::vector<std::string>& known, const char* noun) {
  for (const auto& [key, value] : object.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end())
      fail(source, where + "unknown " + noun + " " + quoted(key) + " (known: " + joined(known) + ")");
  }
}

// `word` of `words` (the field's value), or InputError naming the field and the words.
template <class Enum>
Enum wordField(const std::string& source, const json& doc, const char* field,
               const std::vector<std::pair<std::string, Enum>>& words, Enum fallback) {
  if (!doc.contains(field)) return fallback;
  std::vector<std::string> names;
  for (const auto& [name, value] : words) names.push_back(name);
  const json& given = doc[field];
  if (given.is_string())
    for (const auto& [name, value] : words)
      if (given.get<std::string>() == name) return value;
  fail(source, quoted(field) + ": " + given.dump() + " is not one of " + joined(names));
}

// The entry's options, checked against the kind's, with the defaults of those not given.
json optionsOf(const std::string& source, const std::string& where, const json& entry, const FeatureKind& kind) {
  json options = json::object();
  for (const auto& option : kind.options) options[option.name] = option.defaultValue;
  if (!entry.contains("options")) return options;
  const json& given = entry["options"];
  if (!given.is_object()) fail(source, where + "\"options\" is not an object");
  std::vector<std::string> known;
  for (const auto& option : kind.options) known.push_back(option.name);
  for (const auto& [key, value] : given.items()) {
    const auto option = std::find_if(kind.options.begin(), kind.options.end(),
                                     [&](const features::FeatureOption& o) { return o.name == key; });
    if (option == kind.options.end())
      fail(source, where + "unknown option " + quoted(key) +
                       (known.empty() ? " (the feature has no options)" : " (known: " + joined(known) + ")"));
    if (value.type() != option->defaultValue.type() &&
        !(value.is_number_integer() && option->defaultValue.is_number_integer()))
      fail(source, where + "option " + quoted(key) + ": " + value.dump() + " is not a " +
                       option->defaultValue.type_name() + " like its default " + option->defaultValue.dump());
    options[key] = value;
  }
  return options;
}

// Every feature finds what it needs before it (or in itself), in phase order, once each; the path
// draws the opaque scene once and ends with the display image; max_msaa fits every feature.
void checkComposition(const RenderPath& path, const std::vector<const FeatureKind*>& kinds) {
  const std::string& source = path.source;
  std::map<std::string, std::string> provided;  // product -> who provides it
  if (path.uploadClusters) provided["clusters"] = "\"upload\": {\"clusters\": true}";
  const auto available = [&] {
    std::vector<std::string> names;
    for (const auto& [product, by] : provided) names.push_back(product);
    return names.empty() ? std::string("nothing") : joined(names);
  };
  std::map<std::string, size_t> seen;
  features::FeaturePhase phase = features::FeaturePhase::Lighting;
  size_t phaseEntry = 0;
  for (size_t i = 0; i < kinds.size(); ++i) {
    const FeatureKind& kind = *kinds[i];
    const std::string where = "features[" + std::to_string(i) + "] " + quoted(kind.name) + ": ";
    if (const auto it = seen.find(kind.name); it != seen.end())
      fail(source, where + "given twice (also features[" + std::to_string(it->second) + "])");
    seen[kind.name] = i;
    if (kind.phase < phase) {
      fail(source, where + "a " + features::phaseName(kind.phase) + " feature after features[" +
                       std::to_string(phaseEntry) + "] " + quoted(path.features[phaseEntry].feature) + " (" +
                       features::phaseName(phase) + "); the order is " + features::phaseOrder());
    }
    if (kind.phase > phase) phaseEntry = i;
    phase = std::max(phase, kind.phase);
    if (path.maxMsaa > kind.maxMsaa) {
      fail(source, where + "draws at most " + std::to_string(kind.maxMsaa) + " sample(s) per pixel, but \"max_msaa\" is " +
                       std::to_string(path.maxMsaa));
    }
    const features::FeatureContract contract = kind.contract(path.features[i].options, path);
    for (const std::string& need : contract.needs) {
      const bool own = std::find(contract.provides.begin(), contract.provides.end(), need) != contract.provides.end();
      if (!own && !provided.count(need)) {
        fail(source, where + "needs " + need + ", which no entry before it provides (" + need + " comes from " +
                         features::providersOf(need) + "; available here: " + available() + ")");
      }
    }
    for (const std::string& product : contract.provides) {
      if (const auto it = provided.find(product); it != provided.end())
        fail(source, where + "provides " + product + ", which " + it->second + " already does");
      provided[product] = "features[" + std::to_string(i) + "] " + quoted(kind.name);
    }
  }
  for (const char* product : {"opaque_scene", "display"}) {
    if (!provided.count(product)) {
      fail(source, std::string("no entry provides ") + product + ", which every path needs (it comes from " +
                       features::providersOf(product) + "; the path provides: " + available() + ")");
    }
  }
}

}  // namespace

RenderPath parseRenderPath(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& error) {
    fail(source, std::string("not valid JSON: ") + error.what());
  }
  if (!doc.is_object()) fail(source, "not a JSON object");
  checkKeys(source, "", doc, {"name", "description", "features", "post", "depth_test", "max_msaa", "upload"}, "field");
  RenderPath path;
  path.source = source;
  if (!doc.contains("name") || !doc["name"].is_string() || doc["name"].get<std::string>().empty())
    fail(source, "\"name\" is missing or not a non-empty string");
  path.name = doc["name"].get<std::string>();
  if (doc.contains("description") && !doc["description"].is_string()) fail(source, "\"description\" is not a string");

  using features::DepthTest;
  using features::PostPassForm;
  path.post = wordField<PostPassForm>(source, doc, "post",
                                      {{"fragment", PostPassForm::Fragment}, {"compute", PostPassForm::Compute}},
                                      PostPassForm::Fragment);
  path.depthTest = wordField<DepthTest>(
      source, doc, "depth_test",
      {{"attachment", DepthTest::Attachment}, {"opaque_depth_buffer", DepthTest::OpaqueDepthBuffer}},
      DepthTest::Attachment);
  if (doc.contains("upload")) {
    const json& upload = doc["upload"];
    if (!upload.is_object()) fail(source, "\"upload\" is not an object");
    checkKeys(source, "\"upload\": ", upload, {"clusters"}, "field");
    if (upload.contains("clusters")) {
      if (!upload["clusters"].is_boolean()) fail(source, "\"upload\": \"clusters\" is not true or false");
      path.uploadClusters = upload["clusters"].get<bool>();
    }
  }

  if (!doc.contains("features") || !doc["features"].is_array() || doc["features"].empty())
    fail(source, "\"features\" is missing or not a non-empty array of {\"feature\": NAME, \"options\": {...}}");
  std::vector<const FeatureKind*> kinds;
  for (size_t i = 0; i < doc["features"].size(); ++i) {
    const json& entry = doc["features"][i];
    std::string where = "features[" + std::to_string(i) + "]: ";
    if (!entry.is_object() || !entry.contains("feature") || !entry["feature"].is_string())
      fail(source, where + "expected {\"feature\": NAME, \"options\": {...}}");
    checkKeys(source, where, entry, {"feature", "options"}, "key");
    const std::string name = entry["feature"].get<std::string>();
    const FeatureKind* kind = features::findFeatureKind(name);
    if (!kind) fail(source, where + "unknown feature " + quoted(name) + " (known: " + features::knownFeatureNames() + ")");
    where = "features[" + std::to_string(i) + "] " + quoted(name) + ": ";
    path.features.push_back({name, optionsOf(source, where, entry, *kind)});
    kinds.push_back(kind);
  }

  // max_msaa: by default the most every feature allows.
  path.maxMsaa = 8;
  for (const FeatureKind* kind : kinds) path.maxMsaa = std::min(path.maxMsaa, kind->maxMsaa);
  if (doc.contains("max_msaa")) {
    const json& msaa = doc["max_msaa"];
    const bool valid = msaa.is_number_unsigned() &&
                       (msaa.get<uint32_t>() == 1 || msaa.get<uint32_t>() == 2 || msaa.get<uint32_t>() == 4 ||
                        msaa.get<uint32_t>() == 8);
    if (!valid) fail(source, "\"max_msaa\": " + msaa.dump() + " is not one of 1, 2, 4, 8");
    path.maxMsaa = msaa.get<uint32_t>();
  }
  checkComposition(path, kinds);
  return path;
}

RenderPath loadRenderPath(const std::string& value) {
  for (const features::BuiltinRenderPath& builtin : features::builtinRenderPaths())
    if (builtin.name == value) return parseRenderPath(std::string(builtin.json), value);
  std::string known;
  for (const features::BuiltinRenderPath& builtin : features::builtinRenderPaths())
    known += (known.empty() ? "" : ", ") + std::string(builtin.name);
  if (!value.ends_with(".json")) fail(value, "not a built-in path (" + known + ") nor a FILE.json");
  std::ifstream file(value, std::ios::binary);
  if (!file) fail(value, "cannot read the file (a built-in path is one of " + known + ")");
  std::ostringstream text;
  text << file.rdbuf();
  return parseRenderPath(text.str(), value);
}

RenderPath renderPathOf(const std::map<std::string, std::string>& knobs) {
  const auto it = knobs.find("render.path");
  return loadRenderPath(it == knobs.end() ? std::string("forward") : it->second);
}

RenderPathPlan planRenderPath(const RenderPath& path) {
  RenderPathPlan plan;
  for (const features::RenderPathEntry& entry : path.features) {
    const FeatureKind* kind = features::findFeatureKind(entry.feature);
    if (!kind) throw std::logic_error("render path " + path.source + ": feature " + entry.feature + " is not registered");
    plan.features.push_back(kind->create(entry.options));
    // e.g. "Material Shade" writes the HDR target.
    plan.computeWritesHdr = plan.computeWritesHdr || kind->computeWritesHdr;
  }
  // The compute SSAA Resolve writes the output HDR image, compute tone mapping the display image.
  plan.computeWritesHdr = plan.computeWritesHdr || path.post == features::PostPassForm::Compute;
  plan.computeWritesDisplay = path.post == features::PostPassForm::Compute;
  plan.displayFormat = features::TonemapFeature::displayFormat(path.post);
  return plan;
}

void checkRenderPathSettings(const RenderPath& path, uint32_t requestedMsaa, features::DebugView debugView) {
  using features::DebugView;
  if ((debugView == DebugView::Lod || debugView == DebugView::Clusters) && !path.uploadClusters) {
    throw InputError(std::string("--set debug.view=") + (debugView == DebugView::Lod ? "lod" : "clusters") +
                     ": render.path=" + path.source +
                     " draws no clusters (they colour the clusters that "
                     "render.path=visbuffer and meshlet draw)");
  }
  if (requestedMsaa > path.maxMsaa) {
    throw InputError("--msaa " + std::to_string(requestedMsaa) + ": render.path=" + path.source + " draws at most " +
                     std::to_string(path.maxMsaa) + " sample(s) per pixel (its max_msaa); use --set render.ssaa=N "
                     "for anti-aliasing");
  }
}

void resolveDeviceSettings(features::RenderSettings& settings, const RenderPath& path, const rhi::Device& device) {
  using features::VisBacking;
  const bool imageAtomics = device.shaderCapabilities().imageInt64Atomics;
  if (settings.visBacking == VisBacking::Image && !imageAtomics && path.has("visbuffer")) {
    throw InputError("--set render.vis_backing=image: " + device.adapter().name +
                     " has no 64-bit atomics on R64 storage images; use render.vis_backing=buffer or auto");
  }
  if (settings.visBacking == VisBacking::Auto)
    settings.visBacking = imageAtomics ? VisBacking::Image : VisBacking::Buffer;
}

}  // namespace fgb::render
