#include "feature_registry.hpp"

#include <algorithm>
#include <fgb/core/error.hpp>

#include "bloom/bloom_feature.hpp"
#include "exposure/exposure_feature.hpp"
#include "lighting/clustered_lighting.hpp"
#include "meshes/mesh_feature.hpp"
#include "meshlets/meshlet_feature.hpp"
#include "particles/particle_feature.hpp"
#include "ssaa/msaa_resolve_feature.hpp"
#include "ssaa/ssaa_resolve_feature.hpp"
#include "tonemap/tonemap_feature.hpp"
#include "visbuffer/visbuffer_feature.hpp"

namespace fgb::features {
namespace {

using Options = nlohmann::json;

// A kind with no options and a fixed contract.
template <class Feature>
FeatureKind plain(std::string name, FeaturePhase phase, std::string help, FeatureContract contract) {
  FeatureKind kind;
  kind.name = std::move(name);
  kind.phase = phase;
  kind.help = std::move(help);
  kind.contract = [contract](const Options&, const RenderPath&) { return contract; };
  kind.create = [](const Options&) -> std::unique_ptr<IRenderFeature> { return std::make_unique<Feature>(); };
  return kind;
}

FeatureKind meshes() {
  FeatureKind kind;
  kind.name = "meshes";
  kind.phase = FeaturePhase::SceneColour;
  kind.help = "\"Mesh Frustum Cull\", \"Mesh Render\" (opaque, alpha-masked) and \"Mesh Render Transparent\"";
  kind.options = {
      {"opaque", true, "draws the opaque and alpha-masked scene (\"Mesh Render\"), writing the depth attachment"},
      {"lod", false,
       "draws transparent instances as each mesh's LOD cut at render.lod_error (\"Transparent Cluster Cull\"; "
       "false: full detail)"},
      {"transparent", "raster",
       "raster | compute: transparent instances by \"Mesh Render Transparent\", or (with \"lod\") by \"Transparent "
       "Raster\" and \"Transparent Shade\" in compute; render.transparent overrides it"}};
  kind.contract = [](const Options& options, const RenderPath& path) {
    const std::string transparent = options.at("transparent").get<std::string>();
    if (transparent != "raster" && transparent != "compute")
      throw InputError("--set render.path=" + path.source + ": the meshes option \"transparent\" is \"" + transparent +
                       "\", not raster or compute");
    FeatureContract contract;
    // "Mesh Render Transparent" tests the opaque depth the way the path says; its LOD cut is
    // drawn from the uploaded clusters.
    contract.needs = {depthProductOf(path.depthTest)};
    if (options.at("lod").get<bool>()) contract.needs.push_back("clusters");
    if (options.at("opaque").get<bool>()) contract.provides = {"opaque_scene", "depth_attachment"};
    return contract;
  };
  kind.create = [](const Options& options) -> std::unique_ptr<IRenderFeature> {
    return std::make_unique<MeshFeature>(options.at("opaque").get<bool>(), options.at("lod").get<bool>(),
                                         options.at("transparent").get<std::string>() == "compute");
  };
  return kind;
}

FeatureKind particles() {
  FeatureKind kind = plain<ParticleFeature>("particles", FeaturePhase::SceneColour,
                                            "\"Particle Emit\", \"Particle Update\", \"Particle Render\"", {});
  kind.contract = [](const Options&, const RenderPath& path) {
    return FeatureContract{{depthProductOf(path.depthTest)}, {}};
  };
  return kind;
}

FeatureKind visbuffer() {
  FeatureKind kind;
  kind.name = "visbuffer";
  kind.phase = FeaturePhase::Opaque;
  kind.help = "the compute visibility buffer draws the opaque scene (\"Cluster Cull\" ... \"Material Shade\")";
  kind.options = {{"lod", true, "draws each mesh's LOD cut at render.lod_error (false: full detail)"}};
  kind.contract = [](const Options&, const RenderPath&) {
    return FeatureContract{{"clusters"}, {"opaque_scene", "opaque_depth_buffer"}};
  };
  kind.create = [](const Options& options) -> std::unique_ptr<IRenderFeature> {
    return std::make_unique<VisBufferFeature>(options.at("lod").get<bool>());
  };
  kind.maxMsaa = 1;  // one visibility sample per pixel
  kind.computeWritesHdr = true;  // "Material Shade"
  return kind;
}

FeatureKind meshlets() {
  FeatureKind kind;
  kind.name = "meshlets";
  kind.phase = FeaturePhase::Opaque;
  kind.help =
      "task and mesh shaders draw the opaque scene from the clusters (\"Meshlet Instance Cull\", \"Meshlet Render\")";
  kind.options = {{"lod", true, "draws each mesh's LOD cut at render.lod_error (false: full detail)"}};
  kind.contract = [](const Options&, const RenderPath&) {
    return FeatureContract{{"clusters"}, {"opaque_scene", "depth_attachment"}};
  };
  kind.create = [](const Options& options) -> std::unique_ptr<IRenderFeature> {
    return std::make_unique<MeshletFeature>(options.at("lod").get<bool>());
  };
  return kind;
}

}  // namespace

const char* phaseName(FeaturePhase phase) {
  switch (phase) {
    case FeaturePhase::Lighting: return "lighting";
    case FeaturePhase::Opaque: return "opaque";
    case FeaturePhase::SceneColour: return "scene colour";
    case FeaturePhase::MsaaResolve: return "msaa resolve";
    case FeaturePhase::SsaaResolve: return "ssaa resolve";
    case FeaturePhase::Bloom: return "bloom";
    case FeaturePhase::Exposure: return "exposure";
    case FeaturePhase::ToneMapping: return "tone mapping";
  }
  return "?";
}

std::string phaseOrder() {
  std::string order;
  for (auto phase = uint8_t(FeaturePhase::Lighting); phase <= uint8_t(FeaturePhase::ToneMapping); ++phase)
    order += (order.empty() ? "" : ", ") + std::string(phaseName(FeaturePhase(phase)));
  return order;
}

std::string providersOf(std::string_view product) {
  if (product == "clusters") return "\"upload\": {\"clusters\": true}";
  if (product == "opaque_scene") return "meshes with \"opaque\": true, visbuffer, or meshlets";
  if (product == "depth_attachment") return "meshes with \"opaque\": true, or meshlets";
  std::string names;
  for (const FeatureKind& kind : featureKinds()) {
    // Any path: the contract's products that do not depend on options or the path.
    const RenderPath anyPath;
    Options options = Options::object();
    for (const FeatureOption& option : kind.options) options[option.name] = option.defaultValue;
    const auto provides = kind.contract(options, anyPath).provides;
    if (std::find(provides.begin(), provides.end(), product) != provides.end())
      names += (names.empty() ? "" : ", ") + kind.name;
  }
  return names.empty() ? "no feature" : names;
}

const char* depthProductOf(DepthTest test) {
  return test == DepthTest::Attachment ? "depth_attachment" : "opaque_depth_buffer";
}

const std::vector<FeatureKind>& featureKinds() {
  using enum FeaturePhase;
  static const std::vector<FeatureKind> kinds = {
      plain<ClusteredLighting>("clustered_lighting", Lighting,
                               "\"Cluster Bounds\", \"Clustered Light Cull\": per-cluster light lists",
                               {{}, {"light_lists"}}),
      visbuffer(),
      meshlets(),
      meshes(),
      particles(),
      // After the last feature that draws colour: the MSAA target becomes the HDR image here.
      plain<MsaaResolveFeature>("msaa_resolve", MsaaResolve, "\"MSAA Resolve\" (or \"Clear\" when nothing drew)",
                                {{}, {"hdr"}}),
      plain<SsaaResolveFeature>("ssaa_resolve", SsaaResolve,
                                "\"SSAA Resolve\" (render.ssaa > 1), in the path's post form",
                                {{"hdr"}, {"output_hdr"}}),
      plain<BloomFeature>("bloom", Bloom, "\"Bloom\"", {{"output_hdr"}, {"bloom"}}),
      plain<ExposureFeature>("exposure", Exposure, "\"Exposure\" (post.exposure=auto)", {{"output_hdr"}, {}}),
      plain<TonemapFeature>("tonemap", ToneMapping, "\"Tone mapping\", in the path's post form",
                            {{"output_hdr"}, {"display"}}),
  };
  return kinds;
}

const FeatureKind* findFeatureKind(std::string_view name) {
  for (const FeatureKind& kind : featureKinds())
    if (kind.name == name) return &kind;
  return nullptr;
}

std::string knownFeatureNames() {
  std::vector<std::string> names;
  for (const FeatureKind& kind : featureKinds()) names.push_back(kind.name);
  std::sort(names.begin(), names.end());
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

}  // namespace fgb::features
