// Camera paths: the spline passes through its keyframes and is continuous between them, bad paths
// name the field, and the camera knobs (camera.path, camera.time, camera.distance) land.
#include <fgb/core/error.hpp>
#include <fgb/scene/camera_path.hpp>
#include <fgb/scene/camera_path_cursor.hpp>
#include <fgb/scene/knobs.hpp>
#include <fgb/scene/scene.hpp>
#include <fgb/scene/scene_file.hpp>

#include <glm/geometric.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

using namespace fgb::scene;
using ::testing::HasSubstr;

namespace {

// An uneven path: keys at uneven times, spacings and a sharp turn, one with a field of view.
CameraPath samplePath() {
  return CameraPath({{0.0, {0, 2, 0}, {10, 2, 0}, {}},
                     {1.0, {4, 2, 0}, {10, 2, 3}, 70.0f},
                     {3.5, {4, 2, 9}, {0, 1, 9}, {}},
                     {4.0, {-2, 5, 9}, {0, 0, 0}, {}}});
}

std::string pathError(const std::string& path) {
  try {
    parseSceneText(R"({"camera": {"path": )" + path + "}}", "scenes/walk.json");
  } catch (const fgb::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(CameraPath, PassesThroughEveryKeyframe) {
  const CameraPath path = samplePath();
  const Camera still;
  for (const CameraKey& key : path.keys()) {
    const Camera at = path.at(still, key.time);
    EXPECT_LT(glm::length(at.position - key.position), 1e-9) << "t=" << key.time;
    EXPECT_LT(glm::length(at.target - key.target), 1e-9) << "t=" << key.time;
    EXPECT_FLOAT_EQ(at.verticalFovDeg, key.fovDeg.value_or(still.verticalFovDeg));
  }
}

TEST(CameraPath, ContinuousWithBoundedSpeed) {
  // No jumps: a small time step moves the camera a small distance everywhere, across keys too
  // (the longest chord over the shortest segment bounds the speed of a centripetal spline).
  const CameraPath path = samplePath();
  const Camera still;
  const double dt = 1e-4;
  double fastest = 0.0;
  for (double t = 0.0; t + dt <= path.duration(); t += dt) {
    const double moved = glm::length(path.at(still, t + dt).position - path.at(still, t).position);
    fastest = std::max(fastest, moved / dt);
  }
  EXPECT_GT(fastest, 0.0);
  EXPECT_LT(fastest, 60.0);  // chords of at most ~10 m over segments of at least 0.5 s
  // Both sides of a key agree.
  for (const CameraKey& key : path.keys()) {
    const double t = key.time;
    EXPECT_LT(glm::length(path.at(still, t - 1e-9).position - path.at(still, t + 1e-9).position), 1e-6);
  }
}

TEST(CameraPath, HoldsStillBeyondItsEnds) {
  const CameraPath path = samplePath();
  EXPECT_EQ(path.at({}, -1.0).position, path.keys().front().position);
  EXPECT_EQ(path.at({}, 99.0).position, path.keys().back().position);
  EXPECT_EQ(CameraPath().at(Camera{}, 3.0).position, Camera{}.position);  // no path: the still view
}

// A cursor keeps the segment it last evaluated: walking forward, back, across keys and past the
// ends, and with another still camera's field of view, it gives exactly the cameras a fresh
// evaluation gives.
TEST(CameraPath, ACursorGivesTheSameCamerasAsAFreshEvaluation) {
  const CameraPath path = samplePath();
  CameraPathCursor cursor(path);
  Camera still;
  std::vector<double> times;
  for (int i = -2; i <= 90; ++i) times.push_back(0.05 * i);                  // forward, past both ends
  for (double t : {3.9, 0.2, 1.0, 0.99, 3.5, 2.0, 2.0}) times.push_back(t);  // jumps, keys, repeats
  for (size_t k = 0; k < times.size(); ++k) {
    if (k == times.size() - 1) still.verticalFovDeg = 40.0f;  // same time and segment, another still fov
    const Camera kept = cursor.at(still, times[k]);
    const Camera fresh = CameraPathCursor(path).at(still, times[k]);
    EXPECT_EQ(kept.position, fresh.position) << "t=" << times[k];
    EXPECT_EQ(kept.target, fresh.target) << "t=" << times[k];
    EXPECT_EQ(kept.verticalFovDeg, fresh.verticalFovDeg) << "t=" << times[k];
  }
}

TEST(CameraPath, BadPathsNameTheField) {
  EXPECT_THAT(pathError("[]"), HasSubstr("'camera.path': expected an array of at least 2 keyframes"));
  EXPECT_THAT(pathError(R"([{"time": 0, "position": [0,0,0], "target": [1,0,0]},
                            {"time": 0, "position": [1,0,0], "target": [2,0,0]}])"),
              HasSubstr("'camera.path[1].time': expected a time greater than the previous keyframe's"));
  EXPECT_THAT(pathError(R"([{"time": 1, "position": [0,0,0], "target": [1,0,0]},
                            {"time": 2, "position": [1,0,0], "target": [2,0,0]}])"),
              HasSubstr("'camera.path[0].time': expected 0"));
  EXPECT_THAT(pathError(R"([{"time": 0, "position": [0,0,0], "target": [1,0,0]},
                            {"time": 2, "target": [2,0,0]}])"),
              HasSubstr("'camera.path[1].position'"));
  EXPECT_THAT(pathError(R"([{"time": 0, "position": [0,0,0], "target": [0,0,0]},
                            {"time": 2, "position": [1,0,0], "target": [2,0,0]}])"),
              HasSubstr("'camera.path[0].target': expected a point different from the position"));
  EXPECT_THAT(pathError(R"([{"time": 0, "position": [0,0,0], "target": [1,0,0], "fov": 3},
                            {"time": 2, "position": [1,0,0], "target": [2,0,0]}])"),
              HasSubstr("'camera.path[0].fov': unknown field"));
  EXPECT_THAT(pathError(R"([{"time": 0, "position": [0,0,0], "target": [1,0,0], "fov_deg": 180},
                            {"time": 2, "position": [1,0,0], "target": [2,0,0]}])"),
              HasSubstr("'camera.path[0].fov_deg': expected degrees in (0, 179)"));
  EXPECT_THAT(pathError(R"("none")"), HasSubstr("scenes/walk.json: field 'camera.path'"));
}

TEST(CameraKnobs, TimeDistanceAndNoneLand) {
  Scene scene;
  scene.camera.position = {0, 2, 0};
  scene.camera.target = {10, 2, 0};
  scene.camera.farPlane = 100.0f;
  scene.cameraPath = samplePath();

  Scene still = scene;
  applyKnobs(still, Knobs::parse({"camera.path=none"}));
  EXPECT_TRUE(still.cameraPath.empty());
  EXPECT_FALSE(still.stillTime);

  // The renderer holds the path's view at T; the path and the still camera (the particles'
  // origin) stay as they are.
  Scene atTime = scene;
  applyKnobs(atTime, Knobs::parse({"camera.time=3.5"}));
  ASSERT_TRUE(atTime.stillTime);
  EXPECT_EQ(*atTime.stillTime, 3.5);
  EXPECT_EQ(atTime.camera.position, scene.camera.position);
  EXPECT_LT(glm::length(atTime.cameraPath.at(atTime.camera, 3.5).position - glm::dvec3(4, 2, 9)), 1e-9);

  Scene far = scene;
  applyKnobs(far, Knobs::parse({"camera.distance=4"}));
  EXPECT_LT(glm::length(far.camera.position - glm::dvec3(-30, 2, 0)), 1e-9);  // 4x as far from the target
  EXPECT_FLOAT_EQ(far.camera.farPlane, 400.0f);
  EXPECT_LT(glm::length(far.cameraPath.keys()[0].position - glm::dvec3(-30, 2, 0)), 1e-9);

  Scene infinite = scene;
  applyKnobs(infinite, Knobs::parse({"camera.far=inf", "camera.distance=2"}));
  EXPECT_TRUE(std::isinf(infinite.camera.farPlane));

  EXPECT_THROW(Knobs::parse({"camera.distance=0"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"camera.distance=-1"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"camera.time=-1"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"camera.path=walk"}), fgb::InputError);
}
