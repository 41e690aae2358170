#include "render_settings.hpp"

#include "render_path.hpp"
#include "renderer/shared/debug.h"

#include <fgb/core/error.hpp>

#include <algorithm>
#include <functional>
#include <utility>

namespace fgb::features {

// The shaders read debug.view from FrameConstants::counts.w as these numbers.
static_assert(uint32_t(DebugView::LightComplexity) == gpu::kDebugViewLightComplexity);
static_assert(uint32_t(DebugView::Lod) == gpu::kDebugViewLod);
static_assert(uint32_t(DebugView::Clusters) == gpu::kDebugViewClusters);

namespace {

// One renderer knob, in one line of the table below: its registry entry (type, range, reference
// role and, for approximation and cost-only knobs, the value the sweep's reference uses) and
// where its value lands in RenderSettings. The value arrives parsed once (parseKnobValue).
struct RendererKnob {
  KnobSpec spec;
  std::function<void(RenderSettings&, const KnobValue&)> land;
};

KnobSpec spec(std::string key, KnobType type, std::string help, ReferenceRole role, std::string exact,
              std::vector<std::string> words = {}, double min = 0.0, double max = 0.0) {
  return {std::move(key), type, min, max, false, false, std::move(words), "renderer", std::move(help), role,
          std::move(exact)};
}

// An integer in [min, max] into a uint32_t field.
RendererKnob count(std::string key, double min, double max, uint32_t RenderSettings::*field, std::string help,
                   ReferenceRole role, std::string exact = {}) {
  return {spec(std::move(key), KnobType::Integer, std::move(help), role, std::move(exact), {}, min, max),
          [field](RenderSettings& s, const KnobValue& v) { s.*field = uint32_t(std::get<double>(v)); }};
}
// A finite number in [min, max] into a float field.
RendererKnob number(std::string key, double min, double max, float RenderSettings::*field, std::string help,
                    ReferenceRole role, std::string exact = {}) {
  return {spec(std::move(key), KnobType::Number, std::move(help), role, std::move(exact), {}, min, max),
          [field](RenderSettings& s, const KnobValue& v) { s.*field = float(std::get<double>(v)); }};
}
// 0|1|true|false|on|off into a bool field.
RendererKnob flag(std::string key, bool RenderSettings::*field, std::string help, ReferenceRole role,
                  std::string exact = {}) {
  return {spec(std::move(key), KnobType::Flag, std::move(help), role, std::move(exact)),
          [field](RenderSettings& s, const KnobValue& v) { s.*field = std::get<bool>(v); }};
}
// One of `words` into the field of type T: the words and their values in one list.
template <class T>
RendererKnob word(std::string key, T RenderSettings::*field, std::vector<std::pair<std::string, T>> words,
                  std::string help, ReferenceRole role, std::string exact = {}) {
  std::vector<std::string> names;
  for (const auto& [name, value] : words) names.push_back(name);
  return {spec(std::move(key), KnobType::Word, std::move(help), role, std::move(exact), std::move(names)),
          [field, words](RenderSettings& s, const KnobValue& v) {
            for (const auto& [name, value] : words)
              if (name == std::get<std::string>(v)) s.*field = value;
          }};
}
// Text of `type` (Word with `words`, or Text) into a string field; "none" lands as "".
RendererKnob text(std::string key, KnobType type, std::vector<std::string> words, std::string RenderSettings::*field,
                  std::string help, ReferenceRole role, std::string exact = {}) {
  return {spec(std::move(key), type, std::move(help), role, std::move(exact), std::move(words)),
          [field](RenderSettings& s, const KnobValue& v) {
            const auto& value = std::get<std::string>(v);
            s.*field = value == "none" ? "" : value;
          }};
}

std::vector<std::string> builtinPathNames() {
  std::vector<std::string> names;
  for (const BuiltinRenderPath& path : builtinRenderPaths()) names.emplace_back(path.name);
  return names;
}

const std::vector<RendererKnob>& rendererKnobs() {
  using enum ReferenceRole;
  using S = RenderSettings;
  static const std::vector<RendererKnob> knobs = {
      word("debug.view", &S::debugView,
           {{"none", DebugView::None},
            {"off", DebugView::None},
            {"light-complexity", DebugView::LightComplexity},
            {"lod", DebugView::Lod},
            {"clusters", DebugView::Clusters}},
           "debug visualisation", Look),
      flag("render.depth_prepass", &S::depthPrepass, "depth-only pass before shading", CostOnly, "0"),
      flag("render.async", &S::asyncCompute,
           "compute nodes on a compute queue of their own where the device has one (0: all on graphics)", CostOnly,
           "1"),
      // The sweep's reference raises it to 4 (`fgbench sweep --reference-ssaa` up to 8).
      count("render.ssaa", 1, 8, &S::ssaa, "supersampling: scene passes at S*W x S*H, box-filtered to W x H",
            Approximation, "4"),
      // The reference path is the thesis' forward raster; another path's difference from it at
      // convergence is its bias, which the sweep reports apart from its error. A built-in name
      // (src/renderer/paths/NAME.json, embedded) or a user's FILE.json, which the scene workload
      // reads and checks (scene_workload/render_paths.cpp); it is the path, not a setting, so it
      // lands in no field.
      {spec("render.path", KnobType::WordOrFile,
            "the render path: a built-in one, or a FILE.json naming its features (src/renderer/paths/*.json)", CostOnly,
            "forward", builtinPathNames()),
       [](RenderSettings&, const KnobValue&) {}},
      word("render.vis_backing", &S::visBacking,
           {{"auto", VisBacking::Auto}, {"buffer", VisBacking::Buffer}, {"image", VisBacking::Image}},
           "visbuffer words: R64 image atomics or a storage buffer (auto: image where the device has them)", CostOnly,
           "auto"),
      flag("render.occlusion", &S::occlusion,
           "visbuffer: two-phase HiZ occlusion culling of clusters (no effect on render.path=forward)", CostOnly, "0"),
      // Per-pixel sorting is no approximation of the raster pass's instance order: another cost.
      word(
          "render.transparent", &S::transparentDraw,
          {{"plan", TransparentDraw::Plan}, {"raster", TransparentDraw::Raster}, {"compute", TransparentDraw::Compute}},
          "visbuffer: transparent meshes by the hardware raster, or in compute through a per-pixel K-buffer (plan: "
          "the path's meshes option \"transparent\"; forward and meshlet always raster)",
          CostOnly, "plan"),
      // Exact at 0 (every mesh at full detail): the sweep's reference draws level 0.
      number("render.lod_error", 0, 64, &S::lodError,
             "visbuffer: LOD error in output pixels a cluster cut may show (0: full detail; paths with \"lod\")",
             Approximation, "0"),
      word("lighting.mode", &S::lightingMode, {{"clustered", LightingMode::Clustered}, {"all", LightingMode::All}},
           "clustered light lists, or every light for every pixel", Approximation, "all"),
      // Unused by lighting.mode=all; the largest values make the reference's exactness explicit.
      count("lighting.slices", 1, 64, &S::clusterSlices, "cluster depth slices", Approximation, "64"),
      count("lighting.max_per_cluster", 1, 1024, &S::maxLightsPerCluster, "lights kept per cluster (overflow guard)",
            Approximation, "1024"),
      // A wider bloom is another look, not an approximation that converges (issue 30).
      count("bloom.mips", 1, 10, &S::bloomMips, "bloom chain levels (clamped to what the size allows)", Look),
      count("particles.seed", 0, 1 << 30, &S::particleSeedOffset, "added to every emitter's seed", Content),
      // Phase 2 of render.occlusion has nothing to recover while the camera stands still (phase 1
      // tests against the same depths); this makes it recover clusters (tests: same image).
      flag("debug.occlusion_hold_back", &S::occlusionHoldBack,
           "render.occlusion: phase 1 also holds back every other cluster for phase 2 (tests)", CostOnly, "0"),
      flag("debug.record_every_frame", &S::recordEveryFrame, "record every node every frame (0: reuse unchanged ones)",
           CostOnly, "0"),
      flag("debug.node_buffers", &S::nodeBuffers,
           "one command buffer per node (0: one per submit, kept while no node in it changed)", CostOnly, "0"),
      // The passes whose shaders can write a NaN on request (tests of --check-finite).
      text("debug.inject_nan", KnobType::Word, {"none", "Mesh Render", "Meshlet Render", "Bloom"}, &S::injectNanPass,
           "pass that writes a NaN (tests of --check-finite)", Content),
      // Known faults in known passes (tests of per-pass goldens: the harness must name that pass).
      text("debug.inject_bias", KnobType::Word,
           {"none", "Mesh Render", "Mesh Render Transparent", "Material Shade", "Meshlet Render", "Bloom",
            "Tone mapping"},
           &S::injectBiasPass, "pass whose shader adds a small constant to what it writes (tests of per-pass goldens)",
           Content),
      count("debug.drop_light", 0, 1 << 20, &S::dropLight,
            "K >= 1: \"Clustered Light Cull\" leaves light K-1 out of every cluster (tests of per-pass goldens)",
            Content, "0"),
      // NAME:PERCENT, checked against the frame's passes once the graph is declared (slowPassOf).
      // Slower, not different: pinned off in the sweep's reference.
      text("debug.slow_pass", KnobType::Text, {}, &S::slowPass,
           "NAME:PERCENT: that pass also spins on the GPU for PERCENT% of its own time (timing tests)", CostOnly, ""),
  };
  return knobs;
}

const KnobRegistry& rendererRegistry() {
  static const KnobRegistry registry = [] {
    KnobRegistry r;
    r.add(rendererKnobSpecs());
    return r;
  }();
  return registry;
}

// Prefixes the renderer owns: an unknown key under one of them is a typo, not someone else's knob.
bool underRendererPrefix(const std::string& key) {
  for (const char* prefix : {"debug.", "render.", "lighting.", "bloom.", "particles."})
    if (key.starts_with(prefix)) return true;
  return false;
}

}  // namespace

const std::vector<KnobSpec>& rendererKnobSpecs() {
  static const std::vector<KnobSpec> specs = [] {
    std::vector<KnobSpec> list;
    for (const RendererKnob& knob : rendererKnobs()) list.push_back(knob.spec);
    return list;
  }();
  return specs;
}

bool isRendererKnob(const std::string& key) { return rendererRegistry().find(key) != nullptr; }

void applyRendererKnobs(RenderSettings& settings, const std::map<std::string, std::string>& knobs) {
  for (const auto& [key, value] : knobs) {
    if (!underRendererPrefix(key)) continue;
    const auto& table = rendererKnobs();
    const auto knob = std::find_if(table.begin(), table.end(), [&](const RendererKnob& k) { return k.spec.key == key; });
    if (knob == table.end()) {
      rendererRegistry().check(key, value);  // unknown: throws, naming the known keys
      continue;
    }
    knob->land(settings, parseKnobValue(knob->spec, value));
  }
}

}  // namespace fgb::features
