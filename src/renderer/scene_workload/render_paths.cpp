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
  list.push_back(std::make_unique<features::ClusteredLighting>());
  if (settings.renderPath == features::RenderPath::VisBuffer) {
    list.push_back(std::make_unique<features::VisBufferFeature>());
    plan.computeWritesHdr = true;
  }
  // Forward: every mesh; visbuffer: the transparent ones (MeshFeature reads the path).
  list.push_back(std::make_unique<features::MeshFeature>());
  list.push_back(std::make_unique<features::ParticleFeature>());
  // After the last feature that draws colour: the MSAA target becomes the HDR image here.
  list.push_back(std::make_unique<features::MsaaResolveFeature>());
  list.push_back(std::make_unique<features::SsaaResolveFeature>());
  list.push_back(std::make_unique<features::BloomFeature>());
  list.push_back(std::make_unique<features::ExposureFeature>());  // after bloom: see there
  list.push_back(std::make_unique<features::TonemapFeature>());
  return plan;
}

void checkRenderPathSettings(const features::RenderSettings& settings, uint32_t requestedMsaa) {
  if (settings.renderPath == features::RenderPath::VisBuffer && requestedMsaa > 1) {
    throw InputError("--msaa " + std::to_string(requestedMsaa) +
                     ": render.path=visbuffer has no MSAA (one visibility sample per pixel); use --set render.ssaa=N "
                     "for anti-aliasing");
  }
}

}  // namespace fgb::render
