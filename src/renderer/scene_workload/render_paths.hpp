// Render paths (render.path): the one place that decides what a path is. A path is a JSON file
// (context/render_path.hpp holds its value): the built-in ones, src/renderer/paths/NAME.json, are
// embedded in the binary; `--set render.path=FILE.json` reads a user's. It names the features the
// frame is composed of (in order, with their options: features/feature_registry.hpp), the post
// passes' form, how colour passes after the opaque scene depth-test it, the most MSAA samples and
// what the scene upload includes. Both built-in paths share lights, transparent meshes,
// particles, SSAA resolve, bloom, tone mapping and the light-complexity debug view; they differ in
// what draws the opaque scene:
//   forward:   "Mesh Frustum Cull" + "Mesh Render" (graphics, the thesis' renderer);
//   visbuffer: the compute nodes of features/visbuffer, then the forward passes for the rest; its
//              post passes that can be compute are ("SSAA Resolve", "Tone mapping").
// After the last feature that draws colour, "MSAA Resolve" (features/ssaa) resolves it.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "../features/context/render_feature.hpp"

namespace fgb::render {

// render.path's value (default "forward"): a built-in name, looked up in the embedded table, or a
// FILE.json. The path is checked against the feature registry; a file that cannot be read, is not
// JSON, names an unknown field, feature or option, has a bad value, lists features out of order or
// leaves a feature without an input it needs (or the frame without the opaque scene or the display
// image) throws InputError: one line "--set render.path=VALUE: " naming the entry and what is known.
features::RenderPath loadRenderPath(const std::string& value);
features::RenderPath renderPathOf(const std::map<std::string, std::string>& knobs);

// The same checks on a path's JSON text; `source` names it in messages (render.path's value).
features::RenderPath parseRenderPath(const std::string& text, const std::string& source);

struct RenderPathPlan {
  // In declaration order: producers before consumers.
  std::vector<std::unique_ptr<features::IRenderFeature>> features;
  // A compute node writes the HDR target (it needs storage usage).
  bool computeWritesHdr = false;
  // A compute node writes the display image: storage usage, and a format storage images can have.
  bool computeWritesDisplay = false;
  graph::Format displayFormat = features::kDisplayFormat;
};

// The path's features, created by the registry from its entries, and what the frame's images need.
RenderPathPlan planRenderPath(const features::RenderPath& path);

// The path's constraints on the run's settings (--msaa above its max_msaa; debug.view=lod or clusters
// on a path that draws no clusters); throws InputError naming the option.
void checkRenderPathSettings(const features::RenderPath& path, uint32_t requestedMsaa, features::DebugView debugView);

// Settings that depend on the device, once it is open: render.vis_backing=auto becomes image where
// the device has 64-bit atomics on R64 storage images, else buffer. On a path with the visbuffer
// feature, render.vis_backing=image on a device without them throws InputError naming the knob and
// device.
void resolveDeviceSettings(features::RenderSettings& settings, const features::RenderPath& path,
                           const rhi::Device& device);

}  // namespace fgb::render
