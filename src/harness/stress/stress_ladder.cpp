// Stress ladders: the built-in ones (#17) and custom KEY=V0,V1,... ladders.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fgb/core/error.hpp>
#include <fgb/harness/stress/stress.hpp>
#include <set>

namespace fgb::harness {
namespace {

[[noreturn]] void bad(const std::string& text, const std::string& what) {
  throw InputError("--ladder " + text + ": " + what);
}

std::vector<std::string> splitValues(const std::string& text, const std::string& list) {
  std::vector<std::string> values;
  std::set<std::string> seen;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = std::min(list.find(',', start), list.size());
    std::string value = list.substr(start, comma - start);
    if (value.empty()) bad(text, "empty value");
    if (!seen.insert(value).second) bad(text, "value '" + value + "' repeated");
    values.push_back(std::move(value));
    start = comma + 1;
  }
  if (values.size() < 2) bad(text, "expected a baseline and at least one more rung (V0,V1,...)");
  return values;
}

std::optional<double> number(const std::string& value) {
  double parsed = 0.0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
  if (error != std::errc() || end != value.data() + value.size() || !std::isfinite(parsed)) return std::nullopt;
  return parsed;
}

double numberOrBad(const std::string& text, const std::string& value) {
  const auto parsed = number(value);
  if (!parsed) bad(text, "'" + value + "' is not a number");
  return *parsed;
}

std::pair<uint32_t, uint32_t> sizeOrBad(const std::string& text, const std::string& value) {
  const size_t x = value.find('x');
  const auto w = number(value.substr(0, x));
  const auto h = x == std::string::npos ? std::nullopt : number(value.substr(x + 1));
  if (!w || !h || *w < 1 || *h < 1 || *w != std::floor(*w) || *h != std::floor(*h) || *w > 65536 || *h > 65536)
    bad(text, "'" + value + "' is not a size WxH");
  return {uint32_t(*w), uint32_t(*h)};
}

// A rung setting one knob; the axis is the value when it is a number.
StressRung knobRung(const std::string& key, const std::string& value, double axis, const std::string& series = "") {
  return {value, axis, series, {{key, value}}, 0, 0};
}

StressLadder offsetLadder(const std::string& text, const std::vector<std::string>& values) {
  StressLadder ladder{"offset", "scene.offset (m)", {}, true, {}, ""};
  ladder.thresholds.flipMean = 0.005;
  ladder.description = "whole scene and camera moved by (d, 0, d) m; the image should not change";
  for (const auto& v : values) ladder.rungs.push_back(knobRung("scene.offset", v, numberOrBad(text, v)));
  return ladder;
}

// Near planes with far 1e5, then the same near planes with an infinite far plane.
StressLadder nearLadder(const std::string& text, const std::vector<std::string>& values) {
  StressLadder ladder{"near", "camera.near (m)", {}, true, {}, ""};
  ladder.thresholds.flipMean = 0.002;
  ladder.description = "near plane, with far 1e5 and with far = inf, against the first rung with far 1e5";
  for (const char* far : {"1e5", "inf"}) {
    for (const auto& v : values) {
      const double near = numberOrBad(text, v);
      if (!(near > 0)) bad(text, "near plane '" + v + "' must be > 0");
      const std::string label = std::string(far) == "inf" ? v + " far=inf" : v;
      ladder.rungs.push_back({label, near, std::string("far ") + far, {{"camera.near", v}, {"camera.far", far}}, 0, 0});
    }
  }
  return ladder;
}

// All light scaled by s, the exposure by 1/s: the image should not change.
StressLadder lightScaleLadder(const std::string& text, const std::vector<std::string>& values, const LadderContext& c) {
  StressLadder ladder{"light-scale", "scene.light_scale", {}, true, {}, ""};
  ladder.thresholds.flipMean = 0.01;
  ladder.description = c.autoExposure
                           ? "every light and emissive x s, post.exposure=auto"
                           : fmt::format("every light and emissive x s, post.exposure = {:g} / s", c.exposure);
  for (const auto& v : values) {
    const double scale = numberOrBad(text, v);
    if (!(scale > 0)) bad(text, "scale '" + v + "' must be > 0");
    StressRung rung = knobRung("scene.light_scale", v, scale);
    if (!c.autoExposure) rung.knobs["post.exposure"] = fmt::format("{:.9g}", c.exposure / scale);
    ladder.rungs.push_back(std::move(rung));
  }
  return ladder;
}

StressLadder finiteOnlyLadder(std::string name, std::string key, const std::string& knob, const std::string& text,
                              const std::vector<std::string>& values, std::string description) {
  StressLadder ladder{std::move(name), std::move(key), {}, false, {}, std::move(description)};
  for (const auto& v : values) ladder.rungs.push_back(knobRung(knob, v, numberOrBad(text, v)));
  return ladder;
}

StressLadder resolutionLadder(const std::string& text, const std::vector<std::string>& values) {
  StressLadder ladder{"resolution", "size (pixels)", {}, false, {}, "render size; only finiteness is judged"};
  for (const auto& v : values) {
    const auto [w, h] = sizeOrBad(text, v);
    ladder.rungs.push_back({v, double(w) * double(h), "", {}, w, h});
  }
  return ladder;
}

const std::map<std::string, std::string>& defaultRungs() {
  static const std::map<std::string, std::string> rungs = {
      {"offset", "0,1e3,1e5,1e6,1e7"},        {"near", "1e-1,1e-2,1e-3,1e-4,1e-5,1e-6"},
      {"light-scale", "1,1e-6,1e-3,1e3,1e6"}, {"radiance", "1,1e2,1e4,1e6,1e8"},
      {"fov", "60,1,10,90,150,170"},          {"resolution", "320x180,1x1,2x2,16x9,1280x720,3840x2160"},
  };
  return rungs;
}

StressLadder builtinLadder(const std::string& name, const std::string& text, const std::vector<std::string>& values,
                           const LadderContext& context) {
  if (name == "offset") return offsetLadder(text, values);
  if (name == "near") return nearLadder(text, values);
  if (name == "light-scale") return lightScaleLadder(text, values, context);
  if (name == "radiance") {
    return finiteOnlyLadder("radiance", "scene.emissive_scale", "scene.emissive_scale", text, values,
                            "emissive radiance x s, beyond half-float max; only finiteness is judged");
  }
  if (name == "fov") {
    return finiteOnlyLadder("fov", "camera.fov (degrees)", "camera.fov", text, values,
                            "vertical field of view; only finiteness is judged");
  }
  return resolutionLadder(text, values);
}

}  // namespace

const std::vector<std::string>& builtinLadderNames() {
  static const std::vector<std::string> names = {"offset", "near", "light-scale", "radiance", "fov", "resolution"};
  return names;
}

StressLadder parseLadder(const std::string& text, const LadderContext& context) {
  const size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  if (name.empty()) bad(text, "expected NAME, NAME=V0,V1,... or KEY=V0,V1,...");
  const auto& names = builtinLadderNames();
  const bool builtin = std::find(names.begin(), names.end(), name) != names.end();
  if (equals == std::string::npos) {
    if (!builtin) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
      bad(text, "unknown ladder (built-in: " + known + "; or KEY=V0,V1,...)");
    }
    return builtinLadder(name, text, splitValues(text, defaultRungs().at(name)), context);
  }
  const auto values = splitValues(text, text.substr(equals + 1));
  if (builtin) return builtinLadder(name, text, values, context);
  if (name == "size") return resolutionLadder(text, values);
  // A custom ladder over any knob: invariance is assumed (the baseline is the reference).
  StressLadder ladder{name, name, {}, true, {}, "custom ladder; the image should not change"};
  for (size_t i = 0; i < values.size(); ++i) {
    ladder.rungs.push_back(knobRung(name, values[i], number(values[i]).value_or(double(i + 1))));
  }
  return ladder;
}

}  // namespace fgb::harness
