#include "render_settings.hpp"

#include <fgb/core/error.hpp>

#include <array>
#include <charconv>
#include <string_view>

namespace fgb::features {
namespace {

constexpr std::array<std::string_view, 7> kKeys = {"debug.view",      "render.depth_prepass",     "lighting.slices",
                                                   "lighting.max_per_cluster", "bloom.mips", "particles.seed",
                                                   "render.path"};

[[noreturn]] void badValue(const std::string& key, const std::string& value, const char* expected) {
  throw InputError("--set " + key + "=" + value + ": expected " + expected);
}

uint32_t parseCount(const std::string& key, const std::string& value, uint32_t min, uint32_t max) {
  uint32_t parsed = 0;
  const auto* end = value.data() + value.size();
  const auto [ptr, ec] = std::from_chars(value.data(), end, parsed);
  if (ec != std::errc() || ptr != end || parsed < min || parsed > max) {
    const std::string range = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
    badValue(key, value, range.c_str());
  }
  return parsed;
}

bool parseFlag(const std::string& key, const std::string& value) {
  if (value == "1" || value == "true" || value == "on") return true;
  if (value == "0" || value == "false" || value == "off") return false;
  badValue(key, value, "0|1");
}

DebugView parseDebugView(const std::string& key, const std::string& value) {
  if (value == "none" || value == "off") return DebugView::None;
  if (value == "light-complexity") return DebugView::LightComplexity;
  badValue(key, value, "none|light-complexity");
}

RenderPath parseRenderPath(const std::string& key, const std::string& value) {
  if (value == "forward") return RenderPath::Forward;
  if (value == "visbuffer") return RenderPath::VisBuffer;
  badValue(key, value, "forward|visbuffer");
}

}  // namespace

bool isRendererKnob(const std::string& key) {
  for (const auto known : kKeys)
    if (key == known) return true;
  return false;
}

namespace {
// Prefixes the renderer owns: an unknown key under one of them is a typo, not someone else's knob.
bool underRendererPrefix(const std::string& key) {
  for (const char* prefix : {"debug.", "render.", "lighting.", "bloom.", "particles."})
    if (key.starts_with(prefix)) return true;
  return false;
}
}  // namespace

void applyRendererKnobs(RenderSettings& settings, const std::map<std::string, std::string>& knobs) {
  for (const auto& [key, value] : knobs) {
    if (underRendererPrefix(key) && !isRendererKnob(key)) {
      std::string known;
      for (const auto k : kKeys) known += (known.empty() ? "" : ", ") + std::string(k);
      throw InputError("--set " + key + "=" + value + ": unknown renderer knob (known: " + known + ")");
    }
    if (key == "debug.view") settings.debugView = parseDebugView(key, value);
    else if (key == "render.path") settings.renderPath = parseRenderPath(key, value);
    else if (key == "render.depth_prepass") settings.depthPrepass = parseFlag(key, value);
    else if (key == "lighting.slices") settings.clusterSlices = parseCount(key, value, 1, 64);
    else if (key == "lighting.max_per_cluster") settings.maxLightsPerCluster = parseCount(key, value, 1, 1024);
    else if (key == "bloom.mips") settings.bloomMips = parseCount(key, value, 1, 10);
    else if (key == "particles.seed") settings.particleSeedOffset = parseCount(key, value, 0, 1u << 30);
  }
}

}  // namespace fgb::features
