#include "render_paths.hpp"

#include <fgb/core/error.hpp>
#include <string>

#include "../features/bloom/bloom_feature.hpp"
#include "../features/exposure/exposure_feature.hpp"
#include "../features/lighting/clustered_lighting.hpp"
#include "../features/meshes/mesh_feature.hpp"
#include "../features/particles/particle_feature.hpp"
#include "../features/ssaa/msaa_resolve_feature.hpp"
#include "../features/ssaa/ssaa_resolve_feature.hpp"
#include "../features/tonemap/tonemap_feature.hpp"
#include "../features/visbuffer/visbuffer_feature.hpp"

namespace fgb::render {

RenderPathPlan planRenderPath(const features::RenderSettings& settings) {
  RenderPathPlan plan;
  auto& list = plan.features;
  const bool visBuffer = settings.renderPath == features::RenderPath::VisBuffer;
  // Forward keeps the thesis' full-screen fragment passes; the visibility-buffer path runs them as
  // compute (same GLSL maths), which reaches every SM where graphics runs on a few.
  const auto post = visBuffer ? features::PostPassForm::Compute : features::PostPassForm::Fragment;
  list.push_back(std::make_unique<features::ClusteredLighting>());
  if (visBuffer) list.push_back(std::make_unique<features::VisBufferFeature>());
  // Forward: every mesh; visbuffer: the transparent ones (MeshFeature reads the path).
  list.push_back(std::make_unique<features::MeshFeature>());
  list.push_back(std::make_unique<features::ParticleFeature>());
  // After the last feature that draws colour: the MSAA target becomes the HDR image here.
  list.push_back(std::make_unique<features::MsaaResolveFeature>());
  list.push_back(std::make_unique<features::SsaaResolveFeature>(post));
  list.push_back(std::make_unique<features::BloomFeature>());
  list.push_back(std::make_unique<features::ExposureFeature>());  // after bloom: see there
  list.push_back(std::make_unique<features::TonemapFeature>(post));
  // Material Shade writes the HDR target, and so does the compute SSAA Resolve (the output image).
  plan.computeWritesHdr = visBuffer;
  plan.computeWritesDisplay = post == features::PostPassForm::Compute;
  plan.displayFormat = features::TonemapFeature::displayFormat(post);
  return plan;
}

uint32_t maxMsaaOf(const features::RenderSettings& settings) {
  return settings.renderPath == features::RenderPath::VisBuffer ? 1 : 8;
}

void checkRenderPathSettings(const features::RenderSettings& settings, uint32_t requestedMsaa) {
  if (requestedMsaa > maxMsaaOf(settings)) {
    throw InputError("--msaa " + std::to_string(requestedMsaa) +
                     ": render.path=visbuffer has no MSAA (one visibility sample per pixel); use --set render.ssaa=N "
                     "for anti-aliasing");
  }
}

void resolveDeviceSettings(features::RenderSettings& settings, const rhi::Device& device) {
  using features::VisBacking;
  const bool imageAtomics = device.shaderCapabilities().imageInt64Atomics;
  if (settings.visBacking == VisBacking::Image && !imageAtomics &&
      settings.renderPath == features::RenderPath::VisBuffer) {
    throw InputError("--set render.vis_backing=image: " + device.adapter().name +
                     " has no 64-bit atomics on R64 storage images; use render.vis_backing=buffer or auto");
  }
  if (settings.visBacking == VisBacking::Auto)
    settings.visBacking = imageAtomics ? VisBacking::Image : VisBacking::Buffer;
}

}  // namespace fgb::render
