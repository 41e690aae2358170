// Render paths: which features a frame is composed of, per render.path. Both paths share the
// scene data, lights ("Clustered Light Cull"), transparent meshes, particles, SSAA resolve, bloom,
// tone mapping and the light-complexity debug view; they differ in what draws the opaque scene:
//   forward:   "Mesh Frustum Cull" + "Mesh Render" (graphics, the thesis' renderer);
//   visbuffer: the compute nodes of features/visbuffer, then the forward passes for the rest; its
//              post passes that can be compute are ("SSAA Resolve", "Tone mapping").
// After the last feature that draws colour, "MSAA Resolve" (features/ssaa) resolves it.
#pragma once

#include <memory>
#include <vector>

#include "../features/context/render_feature.hpp"

namespace fgb::render {

struct RenderPathPlan {
  // In declaration order: producers before consumers.
  std::vector<std::unique_ptr<features::IRenderFeature>> features;
  // A compute node writes the HDR target (it needs storage usage).
  bool computeWritesHdr = false;
  // A compute node writes the display image: storage usage, and a format storage images can have.
  bool computeWritesDisplay = false;
  graph::Format displayFormat = features::kDisplayFormat;
};

RenderPathPlan planRenderPath(const features::RenderSettings& settings);

// The most MSAA samples the path draws with (visbuffer: 1, one visibility sample per pixel).
uint32_t maxMsaaOf(const features::RenderSettings& settings);

// The path's constraints on the run's settings; throws InputError naming the option.
void checkRenderPathSettings(const features::RenderSettings& settings, uint32_t requestedMsaa);

// Settings that depend on the device, once it is open: render.vis_backing=auto becomes image where
// the device has 64-bit atomics on R64 storage images, else buffer. On the visbuffer path,
// render.vis_backing=image on a device without them throws InputError naming the knob and device.
void resolveDeviceSettings(features::RenderSettings& settings, const rhi::Device& device);

}  // namespace fgb::render
