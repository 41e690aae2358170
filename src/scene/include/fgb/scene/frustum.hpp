// Camera matrices and the CPU frustum test (AABB against six planes). This is the reference the
// GPU culling pass is checked against: same matrices, same conservative test.
#pragma once

#include <fgb/scene/scene.hpp>

#include <array>

namespace fgb::scene {

// Right-handed view matrix (camera looks down -Z in view space).
glm::mat4 viewMatrix(const Camera& camera);
// Right-handed perspective projection with Vulkan's [0, 1] depth range (no Y flip: the renderer
// applies its own viewport convention; culling does not depend on it).
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

struct Frustum {
  // Planes as (normal, d) with normal pointing inside: a point p is inside when dot(n, p) + d >= 0.
  // Order: left, right, bottom, top, near, far.
  std::array<glm::vec4, 6> planes{};

  // Gribb-Hartmann extraction from a clip-from-world matrix with [0, 1] depth.
  static Frustum fromMatrix(const glm::mat4& clipFromWorld);
  static Frustum fromCamera(const Camera& camera, float aspect);

  // Conservative: false only when the box lies entirely outside one plane (the "p-vertex" test,
  // Assarsson-Moeller). Empty boxes are never visible.
  bool intersects(const Aabb& box) const;
};

struct Visibility {
  uint32_t instances = 0;
  uint64_t triangles = 0;
};

// Instances (and their triangles) whose world bounds intersect the camera's frustum.
Visibility countVisible(const Scene& scene, const Camera& camera, float aspect);

}  // namespace fgb::scene
