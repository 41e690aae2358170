// Frame constants and draw groups: the CPU-side preparation of each frame's values.
#include "gpu_upload.hpp"

#include "../features/context/render_space.hpp"

#include <fgb/scene/frustum.hpp>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace fgb::render {
namespace {

using features::DrawClass;

DrawClass drawClassOf(const scene::Material& material) {
  switch (material.alphaMode) {
    case scene::AlphaMode::Mask: return DrawClass::Masked;
    case scene::AlphaMode::Blend: return DrawClass::Transparent;
    default: return DrawClass::Opaque;
  }
}

constexpr uint32_t kTileSize = 16;

// The far end of the cluster slices: the far plane, or with an infinite one the farthest corner
// of the scene's bounds (no lit fragment lies beyond it).
float clusterFar(const scene::Scene& scene, const scene::Camera& camera) {
  if (std::isfinite(camera.farPlane)) return camera.farPlane;
  const scene::Aabb box = scene::relativeTo(scene.bounds(), camera.position);
  double farthest = 0.0;
  if (!box.isEmpty()) {
    const glm::dvec3 reach = glm::max(glm::abs(box.min), glm::abs(box.max));
    farthest = glm::length(reach);
  }
  return static_cast<float>(std::max(farthest, double(camera.nearPlane) * 1000.0));
}

}  // namespace

gpu::FrameConstants makeFrameConstants(const scene::Scene& scene, const scene::Camera& camera,
                                       const features::RenderSettings& settings) {
  const float aspect = float(settings.width) / float(settings.height);
  gpu::FrameConstants c{};
  c.proj = scene::projectionMatrix(camera, aspect);
  c.proj[1][1] = -c.proj[1][1];  // Vulkan's framebuffer Y points down; keep images upright
  c.invProj = glm::inverse(c.proj);
  if (scene.sun.enabled) {
    c.sunDirection = glm::vec4(glm::normalize(scene.sun.direction), 1.0f);
    c.sunColor = glm::vec4(scene.sun.color * scene.sun.intensity, 0.0f);
  }
  // The scene passes' size (render.ssaa times the output): clusters tile the supersampled image.
  const uint32_t width = settings.sceneWidth();
  const uint32_t height = settings.sceneHeight();
  c.viewport = {float(width), float(height), 1.0f / float(width), 1.0f / float(height)};
  c.depthRange = clusterDepthRange(scene, camera, settings);
  // Tiles cover the same screen area at any render.ssaa (kTileSize output pixels), so SSAA changes
  // neither the cluster count (nor the dispatch size) nor which lights a screen region keeps.
  const uint32_t tile = kTileSize * settings.ssaa;
  c.clusterGrid = {(width + tile - 1) / tile, (height + tile - 1) / tile, settings.clusterSlices, tile};
  // The debug view as the shaders number it (surface_shading.glsl, material_shade.comp).
  c.counts = {uint32_t(scene.lights.size()), uint32_t(scene.instances.size()), settings.maxLightsPerCluster,
              uint32_t(settings.debugView)};
  c.ambient = glm::vec4(glm::vec3(0.03f, 0.03f, 0.035f) * scene.post.lightScale, 0.0f);
  moveCamera(c, scene, camera, settings);
  return c;
}

void moveCamera(gpu::FrameConstants& c, const scene::Scene& scene, const scene::Camera& camera,
                const features::RenderSettings& settings) {
  const features::RenderSpace space = features::RenderSpace::of(scene, camera.position);
  c.view = space.view(camera);
  c.viewProj = c.proj * c.view;
  const auto frustum = scene::Frustum::fromMatrix(c.viewProj);
  for (size_t i = 0; i < frustum.planes.size(); ++i) c.frustumPlanes[i] = frustum.planes[i];
  // Render space is anchored near the camera (render_space.hpp): the view matrix holds the
  // camera's offset from the anchor, and shaders take the eye from cameraPosition.
  c.anchorOffset = glm::vec4(space.point(features::RenderSpace::ofParticles(scene).anchor), 0.0f);
  c.cameraPosition = glm::vec4(space.point(camera.position), 1.0f);
  // Only an infinite far plane makes the slices' far end depend on where the camera is.
  if (!std::isfinite(camera.farPlane)) c.depthRange = clusterDepthRange(scene, camera, settings);
}

glm::vec4 clusterDepthRange(const scene::Scene& scene, const scene::Camera& camera,
                            const features::RenderSettings& settings) {
  // Exponential slices z = near * (far/near)^(slice/slices)  <=>  slice = log(z)*scale + bias, up to
  // a finite far (clusterFar) even when the projection's far plane is infinite.
  const float far = clusterFar(scene, camera);
  const float logRatio = std::log(far / camera.nearPlane);
  const auto slices = float(settings.clusterSlices);
  return {camera.nearPlane, far, slices / logRatio, -slices * std::log(camera.nearPlane) / logRatio};
}

gpu::Exposure initialExposure(const scene::PostSettings& post) {
  gpu::Exposure state{};
  // Auto exposure starts from the scene's exposure, as if the light scale had been compensated;
  // the first frame's measurement replaces it.
  state.preExposure = post.autoExposure ? post.exposure / post.lightScale : post.exposure;
  state.exposure = state.preExposure;
  state.tonemapScale = 1.0f;
  return state;
}

DrawOrder drawOrder(const scene::Scene& scene, const glm::dvec3& cameraPosition) {
  // Opaque and masked instances share a group per (class, mesh); transparent ones get one each.
  std::map<std::pair<DrawClass, uint32_t>, std::vector<uint32_t>> shared;
  std::vector<std::pair<double, uint32_t>> transparent;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const auto& instance = scene.instances[i];
    const DrawClass drawClass = drawClassOf(scene.materials.at(instance.material));
    if (drawClass != DrawClass::Transparent) {
      shared[{drawClass, instance.mesh}].push_back(i);
      continue;
    }
    const glm::dvec3 center = 0.5 * (instance.worldBounds.min + instance.worldBounds.max);
    transparent.emplace_back(glm::distance(center, cameraPosition), i);
  }
  // Back to front: the multi-draw executes commands in order, which is the blend order.
  std::stable_sort(transparent.begin(), transparent.end(), [](auto a, auto b) { return a.first > b.first; });

  DrawOrder order;
  auto addGroup = [&](DrawClass drawClass, uint32_t mesh, const std::vector<uint32_t>& members) {
    features::DrawGroup group{mesh, drawClass, uint32_t(order.instanceOrder.size()), uint32_t(members.size())};
    order.groups.push_back(group);
    order.instanceOrder.insert(order.instanceOrder.end(), members.begin(), members.end());
  };
  for (const auto& [key, members] : shared) addGroup(key.first, key.second, members);
  for (const auto& [distance, index] : transparent) addGroup(DrawClass::Transparent, scene.instances[index].mesh, {index});
  return order;
}

}  // namespace fgb::render
