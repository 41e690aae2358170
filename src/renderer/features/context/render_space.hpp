// Render space: the frame of reference every GPU position is in (instances, bounds, lights,
// particles, the frame constants). World axes, with its origin at an anchor near the camera, so
// the floats the GPU sees stay small however far from the world origin the scene lies (issue 17:
// scene.offset up to 1e8 m); the world-to-render subtraction is done in double on the host.
//
// In a scene with a camera path the anchor is the camera position rounded to the nearest point of a
// grid of kAnchorCell metres, a pure function of the camera position. So a moving camera
// re-anchors only when it crosses into another cell, and only then are the instances, their bounds
// and the lights rewritten; between re-anchorings a frame writes only its constants (the view
// matrix carries camera - anchor). And a still view at camera.time=T has the same anchor, and so
// the same floats, as the path's frame at T. A scene without a path has a camera that never moves,
// which is its own anchor: render space is exactly camera-relative there (the most precise choice,
// and the floats every still-scene golden was blessed with).
#pragma once

#include <fgb/scene/scene.hpp>

#include <glm/ext/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <utility>

namespace fgb::features {

// 16 m: a point near the camera is at most 8 * sqrt(3) ~ 14 m from the anchor, where float's
// spacing is ~1e-6 m. That error is below 1% of a 1080p pixel (60 degrees) from 0.1 m on (the
// default near plane), and a thousandth of a 1 mm gap between two surfaces, so their depth order
// holds. A walk (~2 m/s) re-anchors every ~8 s (atrium-walk: 4 times in 136 frames at 0.25 s;
// city-walk: 11).
inline constexpr double kAnchorCell = 16.0;
// The grid's points on each axis: kAnchorGridOffset + multiples of kAnchorCell. Its cell borders,
// half a cell from them, lie at odd sixteenths of a metre (..., -3.1875, 12.8125, ...), where
// hand-made paths do not run: a camera moving along a border would re-anchor at every wobble (a
// grid through the origin has its borders at +-8 m: the atrium's gallery height and walkway).
// Few bits: grid points and their differences are exact in double, and in float up to 2^24 cells.
inline constexpr double kAnchorGridOffset = 4.8125;

struct RenderSpace {
  glm::dvec3 anchor{0.0};  // world position of render space's origin

  // The render space of `scene`'s camera at `camera` (along its path, if it has one): the one
  // place that decides the anchor.
  static RenderSpace of(const scene::Scene& scene, const glm::dvec3& camera) {
    return scene.cameraPath.empty() ? RenderSpace{camera} : around(camera);
  }
  // The anchor grid's point nearest `camera`.
  static RenderSpace around(const glm::dvec3& camera) {
    glm::dvec3 anchor;
    for (int axis = 0; axis < 3; ++axis)
      anchor[axis] = std::round((camera[axis] - kAnchorGridOffset) / kAnchorCell) * kAnchorCell + kAnchorGridOffset;
    return {anchor};
  }
  // Where the particles' state lives (particle_feature.cpp): the render space of the scene's own
  // camera, fixed for the run, since the simulation keeps its positions from frame to frame. A
  // frame draws them moved by particles.anchor - anchor (FrameConstants::anchorOffset): 0 without a
  // path, else a multiple of kAnchorCell, exact in float.
  static RenderSpace ofParticles(const scene::Scene& scene) { return of(scene, scene.camera.position); }
  bool operator==(const RenderSpace&) const = default;

  // A world point (or a displacement from the anchor) in render space, rounded once to float.
  [[nodiscard]] glm::vec3 point(const glm::dvec3& world) const { return glm::vec3(world - anchor); }

  // The view matrix of `camera` from render space: the camera's rotation and its offset from the
  // anchor, composed in double (the direction keeps its precision far from the origin).
  [[nodiscard]] glm::mat4 view(const scene::Camera& camera) const {
    return glm::mat4(glm::lookAtRH(camera.position - anchor, camera.target - anchor, glm::dvec3(camera.up)));
  }

  // M moved into render space: translate(-anchor) * M, one column at a time (exactly the product:
  // the translation's other terms add zeros), then rounded to float.
  [[nodiscard]] glm::mat4 model(glm::dmat4 m) const {
    for (int column = 0; column < 4; ++column) m[column] -= glm::dvec4(anchor * m[column].w, 0.0);
    return glm::mat4(m);
  }

  // A world box in render space, rounded outwards to float so the GPU's frustum and occlusion
  // tests stay conservative. An empty box stays empty (min > max).
  [[nodiscard]] std::pair<glm::vec4, glm::vec4> bounds(const scene::Aabb& box) const {
    if (box.isEmpty()) return {glm::vec4(1.0f, 1.0f, 1.0f, 0.0f), glm::vec4(-1.0f, -1.0f, -1.0f, 0.0f)};
    glm::vec4 lo(0.0f), hi(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = std::nextafter(static_cast<float>(box.min[axis] - anchor[axis]), -HUGE_VALF);
      hi[axis] = std::nextafter(static_cast<float>(box.max[axis] - anchor[axis]), HUGE_VALF);
    }
    return {lo, hi};
  }
};

}  // namespace fgb::features
