#include "render_settings.hpp"

#include "render_path.hpp"

#include <fgb/core/error.hpp>

#include <charconv>

namespace fgb::features {
namespace {

// Each knob with its reference role (fgb/core/knob_registry.hpp) and, for approximation and
// cost-only knobs, the value the sweep's reference uses.
KnobSpec integer(std::string key, double min, double max, std::string help, ReferenceRole role,
                 std::string exact = {}) {
  return {std::move(key), KnobType::Integer, min, max, false, false, {}, "renderer", std::move(help),
          role,           std::move(exact)};
}
KnobSpec word(std::string key, std::vector<std::string> words, std::string help, ReferenceRole role,
              std::string exact = {}) {
  return {std::move(key), KnobType::Word,  0.0, 0.0, false, false, std::move(words), "renderer", std::move(help),
          role,           std::move(exact)};
}
KnobSpec flag(std::string key, std::string help, ReferenceRole role, std::string exact = {}) {
  return {std::move(key), KnobType::Flag,  0.0, 0.0, false, false, {}, "renderer", std::move(help),
          role,           std::move(exact)};
}

std::vector<std::string> builtinPathNames() {
  std::vector<std::string> names;
  for (const BuiltinRenderPath& path : builtinRenderPaths()) names.emplace_back(path.name);
  return names;
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

// Values reach these only after the registry checked them (type and range).
uint32_t count(const std::string& value) {
  uint32_t parsed = 0;
  std::from_chars(value.data(), value.data() + value.size(), parsed);
  return parsed;
}
bool flag(const std::string& value) { return value == "1" || value == "true" || value == "on"; }
VisBacking visBackingNamed(const std::string& value) {
  if (value == "buffer") return VisBacking::Buffer;
  return value == "image" ? VisBacking::Image : VisBacking::Auto;
}

void applyOne(RenderSettings& settings, const std::string& key, const std::string& value) {
  if (key == "debug.view") settings.debugView = value == "light-complexity" ? DebugView::LightComplexity : DebugView::None;
  else if (key == "render.depth_prepass") settings.depthPrepass = flag(value);
  else if (key == "render.ssaa") settings.ssaa = count(value);
  else if (key == "render.vis_backing") settings.visBacking = visBackingNamed(value);
  else if (key == "render.occlusion") settings.occlusion = flag(value);
  else if (key == "debug.occlusion_hold_back") settings.occlusionHoldBack = flag(value);
  else if (key == "lighting.mode") settings.lightingMode = value == "all" ? LightingMode::All : LightingMode::Clustered;
  else if (key == "lighting.slices") settings.clusterSlices = count(value);
  else if (key == "lighting.max_per_cluster") settings.maxLightsPerCluster = count(value);
  else if (key == "bloom.mips") settings.bloomMips = count(value);
  else if (key == "particles.seed") settings.particleSeedOffset = count(value);
  else if (key == "debug.inject_nan") settings.injectNanPass = value == "none" ? "" : value;
  else if (key == "debug.slow_pass") settings.slowPass = value == "none" ? "" : value;
}

}  // namespace

const std::vector<KnobSpec>& rendererKnobSpecs() {
  using enum ReferenceRole;
  static const std::vector<KnobSpec> specs = {
      word("debug.view", {"none", "off", "light-complexity"}, "debug visualisation", Look),
      flag("render.depth_prepass", "depth-only pass before shading", CostOnly, "0"),
      // The sweep's reference raises it to 4 (`fgbench sweep --reference-ssaa` up to 8).
      integer("render.ssaa", 1, 8, "supersampling: scene passes at S*W x S*H, box-filtered to W x H", Approximation,
              "4"),
      // The reference path is the thesis' forward raster; another path's difference from it at
      // convergence is its bias, which the sweep reports apart from its error. A built-in name
      // (src/renderer/paths/NAME.json, embedded) or a user's FILE.json, which the scene workload
      // reads and checks (scene_workload/render_paths.cpp); it is the path, not a setting.
      {"render.path", KnobType::WordOrFile, 0, 0, false, false, builtinPathNames(), "renderer",
       "the render path: a built-in one, or a FILE.json naming its features (src/renderer/paths/*.json)",
       CostOnly, "forward"},
      word("render.vis_backing", {"auto", "buffer", "image"},
           "visbuffer words: R64 image atomics or a storage buffer (auto: image where the device has them)", CostOnly,
           "auto"),
      flag("render.occlusion",
           "visbuffer: two-phase HiZ occlusion culling of clusters (no effect on render.path=forward)", CostOnly, "0"),
      word("lighting.mode", {"clustered", "all"}, "clustered light lists, or every light for every pixel",
           Approximation, "all"),
      // Unused by lighting.mode=all; the largest values make the reference's exactness explicit.
      integer("lighting.slices", 1, 64, "cluster depth slices", Approximation, "64"),
      integer("lighting.max_per_cluster", 1, 1024, "lights kept per cluster (overflow guard)", Approximation, "1024"),
      // A wider bloom is another look, not an approximation that converges (issue 30).
      integer("bloom.mips", 1, 10, "bloom chain levels (clamped to what the size allows)", Look),
      integer("particles.seed", 0, 1 << 30, "added to every emitter's seed", Content),
      // Phase 2 of render.occlusion has nothing to recover while the camera stands still (phase 1
      // tests against the same depths); this makes it recover clusters (tests: same image).
      flag("debug.occlusion_hold_back",
           "render.occlusion: phase 1 also holds back every other cluster for phase 2 (tests)", CostOnly, "0"),
      // The passes whose shaders can write a NaN on request (tests of --check-finite).
      word("debug.inject_nan", {"none", "Mesh Render", "Bloom"}, "pass that writes a NaN (tests of --check-finite)",
           Content),
      // NAME:PERCENT, checked against the frame's passes once the graph is declared (slowPassOf).
      // Slower, not different: pinned off in the sweep's reference.
      {"debug.slow_pass", KnobType::Text, 0, 0, false, false, {}, "renderer",
       "NAME:PERCENT: that pass also spins on the GPU for PERCENT% of its own time (timing tests)", CostOnly, ""},
  };
  return specs;
}

bool isRendererKnob(const std::string& key) { return rendererRegistry().find(key) != nullptr; }

void applyRendererKnobs(RenderSettings& settings, const std::map<std::string, std::string>& knobs) {
  for (const auto& [key, value] : knobs) {
    if (!underRendererPrefix(key)) continue;
    rendererRegistry().check(key, value);
    applyOne(settings, key, value);
  }
}

}  // namespace fgb::features
