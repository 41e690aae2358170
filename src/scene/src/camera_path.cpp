#include <fgb/scene/camera_path.hpp>
#include <fgb/scene/camera_path_cursor.hpp>
#include <fgb/scene/scene.hpp>

#include "json_fields.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace fgb::scene {
namespace {

// Centripetal knot spacing: sqrt of the chord length. Coincident points (a camera that pauses)
// get a unit spacing so the divisions below stay defined; the segment is then still constant.
double knotStep(const glm::dvec3& a, const glm::dvec3& b) {
  const double step = std::sqrt(glm::length(b - a));
  return step > 1e-12 ? step : 1.0;
}

glm::dvec3 lerp(const glm::dvec3& a, const glm::dvec3& b, double ta, double tb, double t) {
  return (tb - t) / (tb - ta) * a + (t - ta) / (tb - ta) * b;
}

// The centripetal knots t1, t2, t3 of controls p0..p3 (t0 = 0).
void centripetalKnots(const glm::dvec3 (&p)[4], double (&knots)[3]) {
  const double t0 = 0.0;
  knots[0] = t0 + knotStep(p[0], p[1]);
  knots[1] = knots[0] + knotStep(p[1], p[2]);
  knots[2] = knots[1] + knotStep(p[2], p[3]);
}

// Barry and Goldman's pyramid for one centripetal Catmull-Rom segment p1 -> p2 at u in [0, 1]:
// it passes through p1 at u = 0 and p2 at u = 1.
glm::dvec3 centripetal(const glm::dvec3 (&p)[4], const double (&knots)[3], double u) {
  const double t0 = 0.0, t1 = knots[0], t2 = knots[1], t3 = knots[2];
  const double t = t1 + u * (t2 - t1);
  const glm::dvec3 a1 = lerp(p[0], p[1], t0, t1, t), a2 = lerp(p[1], p[2], t1, t2, t), a3 = lerp(p[2], p[3], t2, t3, t);
  const glm::dvec3 b1 = lerp(a1, a2, t0, t2, t), b2 = lerp(a2, a3, t1, t3, t);
  return lerp(b1, b2, t1, t2, t);
}

// Uniform Catmull-Rom of a scalar (the field of view: no chords to measure).
double uniform(double p0, double p1, double p2, double p3, double u) {
  const double u2 = u * u, u3 = u2 * u;
  return 0.5 * (2.0 * p1 + (p2 - p0) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 + (3.0 * p1 - p0 - 3.0 * p2 + p3) * u3);
}

// The four control values of segment i (keys i, i+1), with end points mirrored past the ends.
template <class T, class Get>
void controls(const std::vector<CameraKey>& keys, size_t i, Get get, T (&out)[4]) {
  const size_t last = keys.size() - 1;
  const T p1 = get(keys[i]), p2 = get(keys[i + 1]);
  out[0] = i > 0 ? get(keys[i - 1]) : p1 + p1 - p2;
  out[1] = p1;
  out[2] = p2;
  out[3] = i + 1 < last ? get(keys[i + 2]) : p2 + p2 - p1;
}

}  // namespace

CameraPath::CameraPath(std::vector<CameraKey> keys) : keys_(std::move(keys)) {
  for (size_t i = 1; i < keys_.size(); ++i)
    if (!(keys_[i].time > keys_[i - 1].time)) throw std::invalid_argument("camera path: key times must increase");
}

Camera CameraPath::at(const Camera& still, double time) const {
  return CameraPathCursor(*this).at(still, time);
}

Camera CameraPathCursor::at(const Camera& still, double time) {
  const std::vector<CameraKey>& keys = path_->keys();
  Camera camera = still;
  if (keys.empty()) return camera;
  const auto fov = [&](const CameraKey& key) { return double(key.fovDeg.value_or(still.verticalFovDeg)); };
  if (keys.size() == 1 || time <= keys.front().time || time >= keys.back().time) {
    const CameraKey& end = time >= keys.back().time ? keys.back() : keys.front();
    camera.position = end.position;
    camera.target = end.target;
    camera.verticalFovDeg = float(fov(end));
    return camera;
  }
  // The segment holding `time`: the last key at or before it (the kept one while time stays in it).
  const bool kept = segment_ && segment_->stillFovDeg == still.verticalFovDeg && keys[segment_->index].time <= time &&
                    time < keys[segment_->index + 1].time;
  if (!kept) {
    const auto after =
        std::upper_bound(keys.begin(), keys.end(), time, [](double t, const CameraKey& key) { return t < key.time; });
    Segment& segment = segment_.emplace();
    segment.index = size_t(after - keys.begin()) - 1;
    segment.stillFovDeg = still.verticalFovDeg;
    controls(keys, segment.index, [](const CameraKey& k) { return k.position; }, segment.position);
    controls(keys, segment.index, [](const CameraKey& k) { return k.target; }, segment.target);
    controls(keys, segment.index, fov, segment.fov);
    centripetalKnots(segment.position, segment.positionKnots);
    centripetalKnots(segment.target, segment.targetKnots);
  }
  const Segment& s = *segment_;
  const size_t i = s.index;
  const double u = (time - keys[i].time) / (keys[i + 1].time - keys[i].time);
  camera.position = centripetal(s.position, s.positionKnots, u);
  camera.target = centripetal(s.target, s.targetKnots, u);
  camera.verticalFovDeg = float(std::clamp(uniform(s.fov[0], s.fov[1], s.fov[2], s.fov[3], u), 1.0, 178.0));
  return camera;
}

CameraPath parseCameraPath(const nlohmann::json& keys, const std::string& where) {
  const detail::Fields f(where);
  if (!keys.is_array() || keys.size() < 2) f.fail("camera.path", "an array of at least 2 keyframes", &keys);
  std::vector<CameraKey> result;
  for (size_t i = 0; i < keys.size(); ++i) {
    const std::string field = "camera.path[" + std::to_string(i) + "]";
    const nlohmann::json& key = f.object(keys[i], field);
    f.onlyKeys(key, field, {"time", "position", "target", "fov_deg"});
    for (const char* required : {"time", "position", "target"})
      if (!key.contains(required)) f.fail(field + "." + required, "a value (the field is required)", nullptr);
    CameraKey out;
    out.time = f.number(key["time"], field + ".time");
    if (i == 0 && out.time != 0.0) f.fail(field + ".time", "0 (a path starts at time 0)", &key["time"]);
    if (i > 0 && !(out.time > result.back().time))
      f.fail(field + ".time", "a time greater than the previous keyframe's", &key["time"]);
    out.position = f.dvec3(key["position"], field + ".position");
    out.target = f.dvec3(key["target"], field + ".target");
    if (!(glm::length(out.target - out.position) > 0.0))
      f.fail(field + ".target", "a point different from the position", &key["target"]);
    if (key.contains("fov_deg")) {
      out.fovDeg = f.positive(key["fov_deg"], field + ".fov_deg");
      if (*out.fovDeg >= 179.0f) f.fail(field + ".fov_deg", "degrees in (0, 179)", &key["fov_deg"]);
    }
    result.push_back(out);
  }
  return CameraPath(std::move(result));
}

}  // namespace fgb::scene
