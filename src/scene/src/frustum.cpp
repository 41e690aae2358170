// Frustum extraction and the AABB visibility test.
#include <fgb/scene/frustum.hpp>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace fgb::scene {

glm::mat4 viewMatrix(const Camera& camera) {
  // In double: the direction target - position keeps its precision far from the origin.
  return glm::mat4(glm::lookAtRH(glm::dvec3(0.0), camera.target - camera.position, glm::dvec3(camera.up)));
}

Aabb relativeTo(const Aabb& box, const glm::dvec3& origin) {
  if (box.isEmpty()) return box;
  return Aabb{box.min - origin, box.max - origin};
}

glm::mat4 projectionMatrix(const Camera& camera, float aspect) {
  // Reversed-Z: depth = near / d at view distance d with an infinite far plane, or
  // near * (far - d) / (d * (far - near)) with a finite one; 1 at the near plane, 0 at the far one.
  // With a float depth buffer the exponent spreads the precision evenly over distance.
  const double focal = 1.0 / std::tan(glm::radians(double(camera.verticalFovDeg)) * 0.5);
  const double n = camera.nearPlane;
  const double f = camera.farPlane;
  glm::dmat4 m(0.0);
  m[0][0] = focal / double(aspect);
  m[1][1] = focal;
  m[2][3] = -1.0;
  m[2][2] = std::isinf(f) ? 0.0 : n / (f - n);
  m[3][2] = std::isinf(f) ? n : n * f / (f - n);
  return glm::mat4(m);
}

Frustum Frustum::fromMatrix(const glm::mat4& m) {
  // Rows of the matrix (GLM stores columns).
  auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::vec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  Frustum frustum;
  frustum.planes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2};
  for (glm::vec4& plane : frustum.planes) {
    const float length = glm::length(glm::vec3(plane));
    if (length > 0.0f) plane /= length;
  }
  return frustum;
}

Frustum Frustum::fromCamera(const Camera& camera, float aspect) {
  return fromMatrix(projectionMatrix(camera, aspect) * viewMatrix(camera));
}

bool Frustum::intersects(const Aabb& box) const {
  if (box.isEmpty()) return false;
  for (const glm::vec4& plane : planes) {
    // The box corner furthest along the plane normal: if even it is outside, the box is.
    const glm::dvec3 farthest(plane.x >= 0.0f ? box.max.x : box.min.x, plane.y >= 0.0f ? box.max.y : box.min.y,
                              plane.z >= 0.0f ? box.max.z : box.min.z);
    if (glm::dot(glm::dvec3(plane), farthest) + plane.w < 0.0) return false;
  }
  return true;
}

Visibility countVisible(const Scene& scene, const Camera& camera, float aspect) {
  const Frustum frustum = Frustum::fromCamera(camera, aspect);
  Visibility visibility;
  for (const Instance& instance : scene.instances) {
    if (!frustum.intersects(relativeTo(instance.worldBounds, camera.position))) continue;
    ++visibility.instances;
    visibility.triangles += scene.meshes[instance.mesh].triangleCount();
  }
  return visibility;
}

}  // namespace fgb::scene
