// Uploads a cooked scene to the GPU: geometry, materials, textures with all mips, and creates the
// per-frame buffers (frame_update.hpp writes them before each frame). The copies
// run as one transfer node of a one-off frame graph ("Scene Upload"), whose imports leave every
// resource in the state the frame graph's shaders read it in.
#pragma once

#include "../features/context/gpu_scene.hpp"
#include "../features/context/render_path.hpp"

#include <fgb/rhi/device.hpp>
#include <fgb/scene/scene.hpp>

namespace fgb::render {

// Camera, frustum, sun and cluster parameters for `camera` at the run's resolution (the simulation
// step and flags are the frame update's: frame_update.hpp).
gpu::FrameConstants makeFrameConstants(const scene::Scene& scene, const scene::Camera& camera,
                                       const features::RenderSettings& settings);
// Rewrites only what depends on where `camera` is and looks (view, frustum, render-space offsets),
// for constants made for a camera of the same field of view, near and far planes: the same values
// makeFrameConstants gives, without the projection's inverse and what no move changes.
void moveCamera(gpu::FrameConstants& constants, const scene::Scene& scene, const scene::Camera& camera,
                const features::RenderSettings& settings);
// The cluster slices' depth range (gpu::FrameConstants::depthRange) from `camera`.
glm::vec4 clusterDepthRange(const scene::Scene& scene, const scene::Camera& camera,
                            const features::RenderSettings& settings);

// The exposure state before the first frame: pre-exposed with post.exposure (see gpu::Exposure).
gpu::Exposure initialExposure(const scene::PostSettings& post);

// Instances grouped into indirect draw groups (opaque, masked, transparent back to front from the
// camera). Only the transparent groups' order depends on the camera: every group's first slot and
// size, and the opaque and masked groups, are the same from any position.
struct DrawOrder {
  std::vector<features::DrawGroup> groups;  // in command order: opaque, masked, transparent
  std::vector<uint32_t> instanceOrder;      // GPU instance i is scene instance instanceOrder[i]
};
DrawOrder drawOrder(const scene::Scene& scene, const glm::dvec3& cameraPosition);

// Creates the GPU objects and runs the upload graph to completion; the cooked clusters too where the
// path says ("upload": {"clusters": true}).
features::GpuScene uploadScene(rhi::Device& device, const scene::Scene& scene, const features::RenderSettings& settings,
                               const features::RenderPath& path);

}  // namespace fgb::render
