// Camera matrices and the CPU frustum test (AABB against six planes). This is the reference the
// GPU culling pass is checked against: same matrices, same conservative test.
#pragma once

#include <fgb/scene/scene.hpp>

#include <array>

namespace fgb::scene {

// Right-handed, camera-relative view matrix (camera looks down -Z in view space): a pure rotation
// from render space (world axes, origin at the camera: p_render = p_world - camera.position, in
// double) to view space. It never holds the camera's world translation, so float precision does
// not depend on how far from the world origin the scene is.
glm::mat4 viewMatrix(const Camera& camera);
// `box` (world space) moved so that `origin` is at zero.
Aabb relativeTo(const Aabb& box, const glm::dvec3& origin);
// Right-handed perspective projection with Vulkan's [0, 1] depth range, REVERSED: the near plane
// maps to depth 1 and the far plane to 0; camera.farPlane may be +infinity (then depth -> 0 at
// infinity). Depth buffers clear to 0 and test GREATER_OR_EQUAL. No Y flip: the renderer applies
// its own viewport convention; culling does not depend on it.
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

struct Frustum {
  // Planes as (normal, d) with normal pointing inside: a point p is inside when dot(n, p) + d >= 0.
  // Order: left, right, bottom, top, far, near (reversed-Z: clip z >= 0 is the far plane; with an
  // infinite far plane that plane is (0, 0, 0, near): every point is inside it).
  std::array<glm::vec4, 6> planes{};

  // Gribb-Hartmann extraction from a clip-from-world matrix with [0, 1] depth (either direction).
  static Frustum fromMatrix(const glm::mat4& clipFromWorld);
  // The frustum in render space (camera at the origin); test boxes moved with relativeTo().
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
