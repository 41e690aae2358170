// `fgbench stress SCENE --ladder KEY=V0,V1,...`: numerical stability along one knob. A ladder is a
// one-knob sweep whose reference is its baseline rung V0: every rung renders through the shared
// render path (ConfigurationRenderer, with --check-finite on) and is compared with the baseline by
// the sweep's metrics (LDR-FLIP mean on the display image as frame.png stores it, max abs error,
// share of pixels over 2/255), next to the baseline's own run-to-run noise (a second render of
// V0). Rungs render one after another, one device open at a time (the resolution ladder reaches
// the device's largest image).
//
// Verdict of a rung (documented defaults, overridable; StressThresholds):
//   - any pass wrote a NaN or an Inf -> fail (values above half of R16F's maximum, 32752, are
//     reported, and fail only with overHalfMax);
//   - invariance ladders (the image should not change: offset, near, light-scale, custom keys):
//     FLIP mean - noise FLIP mean > flipMean, or share over 2/255 - noise share > pixelShare, or
//     max abs error > maxAbs -> fail. fov, radiance and resolution change the image by design:
//     only finiteness is judged there.
//   - a rung that fails to render (device error, out of memory) fails with that message.
#pragma once

#include <fgb/harness/metrics/metrics.hpp>
#include <fgb/harness/run/render_path.hpp>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

struct StressThresholds {
  double flipMean = 0.01;    // above the baseline's noise; built-in ladders set their issue targets
  double pixelShare = 0.05;  // share of pixels with a channel off by more than 2/255, above the noise
  double maxAbs = std::numeric_limits<double>::infinity();  // display values in [0, 1]; off by default
  bool nonFinite = true;                                    // a NaN or Inf written by any pass fails
  bool overHalfMax = false;  // a value above half of R16F's maximum (32752) fails too (else: reported)
};

struct StressRung {
  std::string value;                         // as written ("1e6", "1e-4 far=inf", "320x180")
  double axis = 0.0;                         // x on the plot (a log axis over the positive values)
  std::string series;                        // rungs of one series are joined in the plot
  std::map<std::string, std::string> knobs;  // applied on top of the base knobs
  uint32_t width = 0, height = 0;            // resolution ladder; 0: the base size
};

struct StressLadder {
  std::string name;               // "offset", "near", ... or the knob key of a custom ladder
  std::string key;                // what varies, for people ("scene.offset (m)")
  std::vector<StressRung> rungs;  // rungs[0] is the baseline
  bool compareImages = true;      // false: only finiteness is judged (fov, radiance, resolution)
  StressThresholds thresholds;
  std::string description;
};

// Names of the built-in ladders: offset, near, light-scale, radiance, fov, resolution.
const std::vector<std::string>& builtinLadderNames();

// What the scene needs for the built-in ladders: light-scale compensates the exposure (exposure / scale).
struct LadderContext {
  double exposure = 0.6;
  bool autoExposure = false;  // post.exposure=auto compensates by itself: rungs leave the exposure alone
};

// "NAME" (a built-in with its default rungs), "NAME=V0,V1,..." (a built-in with these rungs) or
// "KEY=V0,V1,..." (any --set knob, or width/height/size). Bad text is InputError naming
// `--ladder TEXT`: no values, an empty or repeated value, fewer than two rungs, a value the
// built-in cannot take (a size not WxH, a non-number).
StressLadder parseLadder(const std::string& text, const LadderContext& context);

struct StressRungOutcome {
  StressRung rung;
  bool rendered = false;
  std::string error;  // why it did not render
  RenderedImages images;
  std::vector<render::NonFiniteCounts> nonFinite;  // per checked pass, execution order
  std::optional<ImageMetrics> display;             // against the baseline (compareImages ladders)
  Image heatMap;
  bool pass = true;
  std::string failure;  // "FLIP mean = 0.042 > 0.005 + noise 0.000", ...
};

struct StressResult {
  std::string toolVersion;
  std::string scene;
  render::DeviceDescription device;
  StressLadder ladder;
  ImageMetrics noise;                    // baseline against a second render of it
  std::vector<StressRungOutcome> rungs;  // [0] the baseline
  double wallMs = 0.0;

  // Index of the first failing rung; nullopt when every rung passed.
  std::optional<std::size_t> firstFailure() const;
  // "stable up to 1e6; first failure at 1e7: FLIP mean = 0.474 > 0.005" / "stable through 1e7".
  std::string summary() const;
};

struct StressPlan {
  std::string scene;
  render::WorkloadConfig base;  // size, MSAA, device, knobs every rung shares
  StressLadder ladder;
  uint32_t imageFrame = 2;  // the compared images are of this frame (animated particles)
};

using StressProgress = std::function<void(std::size_t rung, std::size_t rungs, const std::string& value)>;

StressResult runStress(const WorkloadOpener& open, const StressPlan& plan, const StressProgress& progress = {});

// Judges one rung against the baseline's noise (exposed for tests).
void judgeRung(StressRungOutcome& rung, const StressLadder& ladder, const ImageMetrics& noise);

nlohmann::json toJson(const StressResult& result);
std::string stressMarkdown(const StressResult& result);
std::string stressHtml(const StressResult& result);
// stress.json, stress.md, stress.html into `dir` (atomically, each).
void writeStressOutputs(const std::filesystem::path& dir, const StressResult& result);

}  // namespace fgb::harness
