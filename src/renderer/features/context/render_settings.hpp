// Renderer settings: the run's size and MSAA plus the renderer-owned `--set` knobs. Post-processing
// parameters (exposure, bloom) are scene settings (post.* knobs, applied by the scene loader).
#pragma once

#include <fgb/core/knob_registry.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace fgb::features {

// Lod and Clusters colour the visibility-buffer path's opaque pixels by their cluster's LOD level
// and by cluster ("Material Shade"); the forward path shades normally under them.
enum class DebugView : uint8_t { None, LightComplexity, Lod, Clusters };

// render.vis_backing: what holds the visibility buffer's 64-bit words on the visbuffer path. Auto
// becomes Image where the device has 64-bit atomics on R64 storage images, else Buffer; the scene
// workload resolves it once the device is open (features::resolveVisBacking).
enum class VisBacking : uint8_t { Auto, Buffer, Image };

// render.transparent: how the visibility-buffer path draws transparent meshes. Plan: as its plan
// says (the meshes feature's "transparent" option); Raster: "Mesh Render Transparent" (hardware,
// blended in instance order); Compute: "Transparent Raster" and "Transparent Shade" (a per-pixel
// K-buffer, features/transparent_compute/). Paths whose meshes feature has no "lod" (forward,
// meshlet) always raster.
enum class TransparentDraw : uint8_t { Plan, Raster, Compute };

// Clustered: each fragment shades the lights of its cluster (at most lighting.max_per_cluster).
// All: each fragment shades every light, with no cap (the reference; no cluster passes at all).
enum class LightingMode : uint8_t { Clustered, All };

struct RenderSettings {
  uint32_t width = 640;               // output size: the HDR image bloom and tone mapping work on
  uint32_t height = 360;
  uint32_t msaa = 1;
  // render.path is not a setting: it is the path itself (render_path.hpp), which features receive
  // through FeatureInit (scene_workload/render_paths.cpp reads the knob).
  VisBacking visBacking = VisBacking::Auto;     // render.vis_backing = auto | buffer | image
  bool occlusion = false;             // render.occlusion: two-phase HiZ cluster culling (visbuffer)
  TransparentDraw transparentDraw = TransparentDraw::Plan;  // render.transparent = plan | raster | compute
  bool recordEveryFrame = false;      // debug.record_every_frame: no reuse of kept command buffers
  bool nodeBuffers = false;           // debug.node_buffers: a command buffer per node, not per submit
  bool occlusionHoldBack = false;     // debug.occlusion_hold_back: phase 1 also holds back odd clusters
  float lodError = 1.0f;              // render.lod_error: output pixels of LOD error (visbuffer; 0: full detail)
  uint32_t ssaa = 1;                  // render.ssaa: scene passes at ssaa*width x ssaa*height
  bool depthPrepass = false;          // render.depth_prepass
  // render.async: compute nodes run on a compute queue of their own where the device has one
  // (async compute); off, every node runs on the graphics queue (rhi::GraphOptions::queues = 1).
  bool asyncCompute = true;
  DebugView debugView = DebugView::None;  // debug.view = none | light-complexity | lod | clusters
  LightingMode lightingMode = LightingMode::Clustered;  // lighting.mode = clustered | all
  uint32_t clusterSlices = 24;        // lighting.slices
  uint32_t maxLightsPerCluster = 128; // lighting.max_per_cluster (overflow guard)
  uint32_t bloomMips = 6;             // bloom.mips
  uint32_t particleSeedOffset = 0;    // particles.seed (added to every emitter's seed)
  bool checkFinite = false;           // --check-finite (not a knob: a run option)
  bool capture = false;               // --capture (a run option): PassCaptureFeature declares copies
  std::string injectNanPass;          // debug.inject_nan: the pass whose shader writes a NaN ("": none)
  std::string injectBiasPass;         // debug.inject_bias: the pass whose shader adds kInjectedBias ("": none)
  uint32_t dropLight = 0;             // debug.drop_light: K >= 1 leaves light K-1 out of every cluster (0: none)
  std::string slowPass;               // debug.slow_pass: "NAME:PERCENT" as given ("": none)

  // Size the scene passes (meshes, lights, particles) render at: the output size times render.ssaa.
  [[nodiscard]] uint32_t sceneWidth() const { return width * ssaa; }
  [[nodiscard]] uint32_t sceneHeight() const { return height * ssaa; }
  // The LOD cut's error bound in scene pixels: render.lod_error is in output pixels, and the scene
  // passes have render.ssaa times as many.
  [[nodiscard]] float lodThresholdScenePixels() const { return lodError * float(ssaa); }
};

// The renderer's entries of the knob registry (every key below, with its type and range).
const std::vector<KnobSpec>& rendererKnobSpecs();

// debug.slow_pass=NAME:PERCENT, checked against the names of the frame's declared passes: the
// pass and PERCENT / 100 (0 < PERCENT <= 10000). InputError (one line naming the knob, and the
// known passes when the name is not one) otherwise.
struct SlowPass {
  std::string pass;
  double fraction = 0.0;
};
SlowPass slowPassOf(const std::string& value, const std::vector<std::string>& passes);

// Keys of the renderer knobs.
bool isRendererKnob(const std::string& key);

// Applies the renderer-owned knobs; keys outside the renderer's prefixes are ignored (they belong to
// the scene or harness). Throws fgb::InputError "--set key=value: ..." for an unknown key under a
// renderer prefix and for a malformed or out-of-range value.
void applyRendererKnobs(RenderSettings& settings, const std::map<std::string, std::string>& knobs);

}  // namespace fgb::features
