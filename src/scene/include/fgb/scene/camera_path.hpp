// Camera paths (scene files' camera.path): keyframes of time, position, target and optionally the
// field of view, joined by a centripetal Catmull-Rom spline (Yuksel et al. 2011: no cusps or
// self-intersections within a segment, unlike the uniform form) through every keyframe.
#pragma once

#include <glm/ext/vector_double3.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace fgb::scene {

struct Camera;  // scene.hpp, which includes this header

struct CameraKey {
  double time = 0.0;  // seconds, strictly increasing along the path
  glm::dvec3 position{0.0};
  glm::dvec3 target{0.0};
  std::optional<float> fovDeg;  // vertical field of view; keys without one keep the still camera's
};

class CameraPath {
 public:
  CameraPath() = default;
  // Keys in time order (checked by parseCameraPath; throws std::invalid_argument otherwise).
  explicit CameraPath(std::vector<CameraKey> keys);

  [[nodiscard]] bool empty() const { return keys_.empty(); }
  [[nodiscard]] double duration() const { return keys_.empty() ? 0.0 : keys_.back().time; }
  [[nodiscard]] const std::vector<CameraKey>& keys() const { return keys_; }
  [[nodiscard]] std::vector<CameraKey>& keys() { return keys_; }

  // The camera at `time`: `still` (up, near, far, fov) with the path's position, target and fov.
  // Before the first key and after the last the path holds still there.
  [[nodiscard]] Camera at(const Camera& still, double time) const;

 private:
  std::vector<CameraKey> keys_;
};

// Reads camera.path: an array of at least two {"time", "position", "target", "fov_deg"?} objects
// with strictly increasing times, the first at 0. InputError "<where>: camera.path[i].field: ...".
CameraPath parseCameraPath(const nlohmann::json& keys, const std::string& where);

}  // namespace fgb::scene
