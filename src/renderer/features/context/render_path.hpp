// A render path (render.path) as one value: every decision in which render paths differ. The
// built-in paths are JSON files (src/renderer/paths/NAME.json, embedded in the binary); a user's
// FILE.json has the same form. scene_workload/render_paths.cpp reads and checks a path against the
// feature registry (features/feature_registry.hpp) and composes its features; each feature gets the
// path through FeatureInit and reads the decisions that concern it from here, never which path runs.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::features {

// How a full-screen post pass runs: as a fragment pass (the thesis' forward renderer) or as a
// compute dispatch on the graphics queue (the visibility-buffer path: on GPUs that run graphics on
// a few SMs only, compute reaches all of them). Both forms share their GLSL maths.
enum class PostPassForm : uint8_t { Fragment, Compute };

// How the colour passes drawn after the opaque scene ("Mesh Render Transparent", "Particle
// Render") depth-test against it. Forward: the depth attachment, kDepthCompare in the pipeline.
// Visibility buffer: no depth attachment (the opaque depth is a buffer "Material Shade" writes,
// FrameTargets::opaqueDepth); the fragment shaders' "opaque_depth" variants (setDepthState picks
// them) read it and discard what the attachment's test would reject (include/opaque_depth.glsl).
// The pipelines differ (a depth format or none), so a feature takes the form from the path once,
// at initialisation.
enum class DepthTest : uint8_t { Attachment, OpaqueDepthBuffer };

// One entry of a path's feature list: a feature of the registry and its options, checked against
// the options the registry entry declares, with the defaults of those not given filled in.
struct RenderPathEntry {
  std::string feature;
  nlohmann::json options = nlohmann::json::object();
};

struct RenderPath {
  std::string name;    // the file's "name"
  std::string source;  // render.path's value: the built-in name or the file as given (messages)
  // In declaration order: producers before consumers (the registry's phases).
  std::vector<RenderPathEntry> features;
  PostPassForm post = PostPassForm::Fragment;   // "post": fragment | compute
  DepthTest depthTest = DepthTest::Attachment;  // "depth_test": attachment | opaque_depth_buffer
  uint32_t maxMsaa = 8;                         // "max_msaa": the most MSAA samples the path draws with
  bool uploadClusters = false;                  // "upload": {"clusters": ...}: the cooked clusters go to the GPU

  [[nodiscard]] bool has(std::string_view feature) const {
    for (const RenderPathEntry& entry : features)
      if (entry.feature == feature) return true;
    return false;
  }
};

// The built-in paths, embedded from src/renderer/paths/*.json at build time (generated source).
struct BuiltinRenderPath {
  std::string_view name;  // the file's name without .json
  std::string_view json;  // its text
};
std::span<const BuiltinRenderPath> builtinRenderPaths();

}  // namespace fgb::features
