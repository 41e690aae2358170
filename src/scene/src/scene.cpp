// Small value-type helpers of the scene model.
#include <fgb/scene/scene.hpp>

#include <glm/common.hpp>

#include <array>
#include <limits>

namespace fgb::scene {

Aabb Aabb::empty() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return Aabb{glm::dvec3(inf), glm::dvec3(-inf)};
}

void Aabb::extend(const glm::dvec3& point) {
  min = glm::min(min, point);
  max = glm::max(max, point);
}

void Aabb::extend(const Aabb& other) {
  if (other.isEmpty()) return;
  min = glm::min(min, other.min);
  max = glm::max(max, other.max);
}

Aabb Aabb::transformed(const glm::dmat4& transform) const {
  if (isEmpty()) return *this;
  // Arvo's method: the transformed box is the translation plus, per axis, the sum of the
  // smaller/larger products -- exact for the eight corners, without enumerating them.
  const glm::dvec3 translation(transform[3]);
  Aabb result{translation, translation};
  for (int column = 0; column < 3; ++column) {
    for (int row = 0; row < 3; ++row) {
      const double a = transform[column][row] * min[column];
      const double b = transform[column][row] * max[column];
      result.min[row] += a < b ? a : b;
      result.max[row] += a < b ? b : a;
    }
  }
  return result;
}

uint64_t RepairCounters::total() const {
  return nonFinitePositions + nonFiniteTriangles + nonFiniteNormals + zeroNormals + nonFiniteTangents + zeroTangents +
         nonFiniteUvs + degenerateTriangles + zeroAreaTriangles + nonTrianglePrimitives +
         generatedNormals + generatedTangents + missingTextures + emptyMeshes;
}

RepairCounters& RepairCounters::operator+=(const RepairCounters& o) {
  nonFinitePositions += o.nonFinitePositions;
  nonFiniteTriangles += o.nonFiniteTriangles;
  nonFiniteNormals += o.nonFiniteNormals;
  zeroNormals += o.zeroNormals;
  nonFiniteTangents += o.nonFiniteTangents;
  zeroTangents += o.zeroTangents;
  nonFiniteUvs += o.nonFiniteUvs;
  degenerateTriangles += o.degenerateTriangles;
  zeroAreaTriangles += o.zeroAreaTriangles;
  nonTrianglePrimitives += o.nonTrianglePrimitives;
  generatedNormals += o.generatedNormals;
  generatedTangents += o.generatedTangents;
  missingTextures += o.missingTextures;
  emptyMeshes += o.emptyMeshes;
  return *this;
}

Aabb Scene::bounds() const {
  Aabb box = Aabb::empty();
  for (const Instance& instance : instances) box.extend(instance.worldBounds);
  return box;
}

}  // namespace fgb::scene
