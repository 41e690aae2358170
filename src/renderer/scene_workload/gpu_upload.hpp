// Uploads a cooked scene to the GPU: geometry, instances (ordered by draw group), materials,
// lights, frame constants, the indirect-command template and textures with all mips. The copies
// run as one transfer node of a one-off frame graph ("Scene Upload"), whose imports leave every
// resource in the state the frame graph's shaders read it in.
#pragma once

#include "../features/context/gpu_scene.hpp"
#include "../features/context/render_path.hpp"

#include <fgb/rhi/device.hpp>
#include <fgb/scene/scene.hpp>

namespace fgb::render {

// Camera, sun and cluster parameters for the scene's camera at the run's resolution.
gpu::FrameConstants makeFrameConstants(const scene::Scene& scene, const features::RenderSettings& settings);

// The exposure state before the first frame: pre-exposed with post.exposure (see gpu::Exposure).
gpu::Exposure initialExposure(const scene::PostSettings& post);

// Instances grouped into indirect draw groups (opaque, masked, transparent back to front).
void buildDrawGroups(const scene::Scene& scene, const glm::dvec3& cameraPosition, features::GpuScene& gpu);

// Creates the GPU objects and runs the upload graph to completion; the cooked clusters too where the
// path says ("upload": {"clusters": true}).
features::GpuScene uploadScene(rhi::Device& device, const scene::Scene& scene, const features::RenderSettings& settings,
                               const features::RenderPath& path);

}  // namespace fgb::render
