// A cursor over a camera path (camera_path.hpp) for a run of times, as a flown path's frames ask.
#pragma once

#include <fgb/scene/camera_path.hpp>
#include <fgb/scene/scene.hpp>

#include <glm/ext/vector_double3.hpp>

#include <cstddef>
#include <optional>

namespace fgb::scene {

// Evaluates one path at a run of times (a flown path, frame after frame), keeping the segment it
// last evaluated: its control points, the centripetal knots of its positions and targets and its
// field-of-view controls. A time in the same segment then costs only the interpolation; the
// cameras are exactly CameraPath::at's (which is a cursor used once).
// The path must not change while a cursor is in use.
class CameraPathCursor {
 public:
  explicit CameraPathCursor(const CameraPath& path) : path_(&path) {}
  [[nodiscard]] Camera at(const Camera& still, double time);

 private:
  // Segment i's controls (keys i-1 .. i+2, the ends mirrored) and knots t1..t3 (t0 = 0).
  struct Segment {
    size_t index = 0;
    float stillFovDeg = 0.0f;  // the fov of keys without one
    glm::dvec3 position[4], target[4];
    double positionKnots[3] = {}, targetKnots[3] = {};
    double fov[4] = {};
  };

  const CameraPath* path_;
  std::optional<Segment> segment_;
};

}  // namespace fgb::scene
