// Anchor-relative render space (features/context/render_space.hpp): the anchor snaps to a grid, so
// a camera moving within its cell keeps the instances, bounds and lights a frame in flight's copy
// holds, and a frame writes only its constants (frame_update.hpp: InstanceWriter, CopyContents).
#include "features/context/render_space.hpp"
#include "scene_workload/frame_update.hpp"
#include "scene_workload/gpu_upload.hpp"

#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <vector>

namespace fgb::render {
namespace {

using features::kAnchorCell;
using features::RenderSpace;
using Write = CopyContents::Write;

TEST(RenderSpace, AnchorIsTheNearestGridPointAndItsOffsetIsExactFarFromTheOrigin) {
  for (const double offset : {0.0, 1e3, 1e6, 1e8, -1e8}) {
    const glm::dvec3 camera = glm::dvec3(offset) + glm::dvec3(3.3, -7.9, 8.1);
    const RenderSpace space = RenderSpace::around(camera);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(std::fmod(space.anchor[axis] - features::kAnchorGridOffset, kAnchorCell), 0.0) << offset;
      EXPECT_LE(std::abs(camera[axis] - space.anchor[axis]), kAnchorCell / 2) << offset;
      // The subtraction is exact, so the float offset is the camera's own, rounded once.
      EXPECT_EQ(space.anchor[axis] + (camera[axis] - space.anchor[axis]), camera[axis]) << offset;
    }
  }
}

TEST(RenderSpace, MovingWithinACellKeepsTheAnchorAndCrossingItsEdgeMovesIt) {
  // 1e7 is a multiple of the cell: the borders there lie at 1e7 + 12.8125 and 1e7 - 3.1875.
  const RenderSpace space = RenderSpace::around({1e7 + 1.0, 1.7, -2.0});
  EXPECT_EQ(space.anchor, glm::dvec3(1e7, 0.0, 0.0) + glm::dvec3(features::kAnchorGridOffset));
  EXPECT_EQ(RenderSpace::around({1e7 + 12.8, 8.0, -3.18}), space);
  EXPECT_NE(RenderSpace::around({1e7 + 12.82, 1.7, -2.0}), space);
  EXPECT_NE(RenderSpace::around({1e7 + 1.0, 1.7, -3.2}), space);
}

TEST(RenderSpace, ModelAndBoundsAreTheWorldsMinusTheAnchor) {
  const RenderSpace space = RenderSpace::around({1e8 + 5.0, 0.0, 0.0});
  ASSERT_EQ(space.anchor, glm::dvec3(1e8, 0.0, 0.0) + glm::dvec3(features::kAnchorGridOffset));
  const glm::dmat4 transform = glm::translate(glm::dmat4(1.0), glm::dvec3(1e8 + 20.0, 3.0, -4.0));
  const glm::mat4 model = space.model(transform);
  EXPECT_EQ(model[3], glm::vec4(15.1875f, -1.8125f, -8.8125f, 1.0f));
  EXPECT_EQ(model[0], glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  const auto [lo, hi] = space.bounds({{1e8 + 1.0, -1.0, -1.0}, {1e8 + 3.0, 1.0, 1.0}});
  // Rounded outwards: the float box holds the double one (-3.8125 .. -1.8125 in x).
  EXPECT_LT(lo.x, -3.8125f);
  EXPECT_GT(lo.x, -3.8126f);
  EXPECT_GT(hi.x, -1.8125f);
  EXPECT_LT(hi.x, -1.8124f);
}

TEST(RenderSpace, AStillSceneIsAnchoredAtItsCameraAndAPathsFramesOnTheGrid) {
  scene::Scene s;
  s.camera.position = {1e8 + 5.5, 1.7, -3.25};
  EXPECT_EQ(RenderSpace::of(s, s.camera.position).anchor, s.camera.position);
  EXPECT_EQ(RenderSpace::ofParticles(s).anchor, s.camera.position);
  s.cameraPath = scene::CameraPath({{0.0, s.camera.position, {}, {}}, {1.0, s.camera.position + 1.0, {}, {}}});
  EXPECT_EQ(RenderSpace::of(s, s.camera.position), RenderSpace::around(s.camera.position));
  EXPECT_EQ(RenderSpace::ofParticles(s), RenderSpace::around(s.camera.position));
}

TEST(FrameConstants, TheEyeIsAtCameraPositionInAnchoredRenderSpace) {
  scene::Scene s;
  s.camera.position = {1e8 + 5.5, 1.7, -3.25};
  s.camera.target = {1e8 + 30.0, 2.0, -40.0};
  scene::Camera moved = s.camera;
  moved.position += glm::dvec3(2.0, 0.0, -1.0);
  moved.target += glm::dvec3(2.0, 0.0, -1.0);
  s.cameraPath = scene::CameraPath({{0.0, s.camera.position, s.camera.target, {}}, {1.0, moved.position, moved.target, {}}});
  features::RenderSettings settings;
  const auto c = makeFrameConstants(s, moved, settings);
  const RenderSpace space = RenderSpace::around(moved.position);
  ASSERT_NE(space.anchor, moved.position);
  EXPECT_EQ(glm::vec3(c.cameraPosition), glm::vec3(moved.position - space.anchor));
  EXPECT_EQ(c.cameraPosition.w, 1.0f);
  // The view takes the eye to view space's origin and the target straight ahead (-Z).
  const glm::vec4 eye = c.view * c.cameraPosition;
  EXPECT_LT(glm::length(glm::vec3(eye)), 1e-5f);
  const glm::vec4 ahead = c.view * glm::vec4(space.point(moved.target), 1.0f);
  EXPECT_NEAR(ahead.x, 0.0f, 1e-4f);
  EXPECT_NEAR(ahead.y, 0.0f, 1e-4f);
  EXPECT_LT(ahead.z, -30.0f);
  // The target is inside every frustum plane, the eye's mirror behind it is not.
  const glm::vec3 behind = glm::vec3(c.cameraPosition) - (space.point(moved.target) - glm::vec3(c.cameraPosition));
  bool behindInside = true;
  for (const glm::vec4& plane : c.frustumPlanes) {
    EXPECT_GE(glm::dot(glm::vec3(plane), space.point(moved.target)) + plane.w, 0.0f);
    behindInside = behindInside && glm::dot(glm::vec3(plane), behind) + plane.w >= 0.0f;
  }
  EXPECT_FALSE(behindInside);
  // Particles live in the scene camera's render space; the offset moves them into this frame's.
  EXPECT_EQ(glm::dvec3(glm::vec3(c.anchorOffset)), RenderSpace::ofParticles(s).anchor - space.anchor);
}

// A moving camera of one field of view rewrites only the view's part of its constants
// (FrameUpdate): that must give every byte makeFrameConstants gives, with a finite far plane and
// with an infinite one (whose cluster slices end where the scene does, seen from the camera).
TEST(RenderSpace, MovingTheCameraGivesTheConstantsMadeAfresh) {
  scene::Scene s;
  s.cameraPath =
      scene::CameraPath({{0.0, {0.0, 1.0, 0.0}, {0.0, 1.0, -1.0}, {}}, {1.0, {30.0, 2.0, 5.0}, {0.0, 1.0, 0.0}, {}}});
  scene::Instance instance;
  instance.worldBounds = {{-50.0, 0.0, -50.0}, {50.0, 10.0, 50.0}};
  s.instances.push_back(instance);
  features::RenderSettings settings;
  settings.width = 320;
  settings.height = 180;
  for (const float far : {500.0f, INFINITY}) {
    scene::Camera from = s.camera;
    from.farPlane = far;
    scene::Camera to = from;
    from.position = {1.0, 1.7, 2.0};
    to.position = {29.0, 2.5, -3.0};  // another anchor cell
    to.target = {0.0, 0.0, -9.0};
    gpu::FrameConstants moved = makeFrameConstants(s, from, settings);
    moveCamera(moved, s, to, settings);
    const gpu::FrameConstants fresh = makeFrameConstants(s, to, settings);
    EXPECT_EQ(std::memcmp(&moved, &fresh, sizeof(fresh)), 0) << "far " << far;
    const gpu::FrameConstants before = makeFrameConstants(s, from, settings);
    EXPECT_NE(std::memcmp(&moved, &before, sizeof(fresh)), 0);  // the move did change them
  }
}

scene::Scene twoOpaqueTwoTransparent() {
  scene::Scene s;
  s.meshes.resize(2);
  s.meshes[1].firstIndex = 30;
  s.materials.resize(2);
  s.materials[1].alphaMode = scene::AlphaMode::Blend;
  auto add = [&](uint32_t mesh, uint32_t material, double z) {
    scene::Instance instance;
    instance.mesh = mesh;
    instance.material = material;
    instance.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, z));
    instance.worldBounds = {{-1.0, -1.0, z - 1.0}, {1.0, 1.0, z + 1.0}};
    s.instances.push_back(instance);
  };
  add(0, 0, 0.0);    // opaque
  add(1, 1, -5.0);   // transparent
  add(0, 0, -20.0);  // opaque
  add(1, 1, -30.0);  // transparent
  s.camera.position = {0.0, 0.0, 10.0};
  return s;
}

TEST(InstanceWriter, WritesEveryInstanceInItsRenderSpaceAndTheTransparentOnesAlone) {
  const scene::Scene s = twoOpaqueTwoTransparent();
  InstanceWriter writer(s);
  std::vector<gpu::Instance> instances(4);
  std::vector<gpu::DrawCommand> commands(3);  // one opaque group, two transparent
  writer.sortTransparent({0.0, 0.0, 10.0});
  const RenderSpace space = RenderSpace::around({0.0, 0.0, 10.0});
  ASSERT_EQ(space.anchor, glm::dvec3(4.8125));
  writer.writeAll(space, instances, commands);
  // Opaque first, then the transparent ones back to front: the farther (z = -30) first.
  EXPECT_EQ(instances[2].model[3], glm::vec4(-4.8125f, -4.8125f, -34.8125f, 1.0f));
  EXPECT_EQ(instances[3].model[3], glm::vec4(-4.8125f, -4.8125f, -9.8125f, 1.0f));
  EXPECT_EQ(instances[3].drawGroup, 2u);
  EXPECT_EQ(commands[2].firstInstance, 3u);
  EXPECT_EQ(commands[2].firstIndex, 30u);

  // From beyond both (z = -40) the order turns around; only the transparent part is written.
  const std::vector<uint32_t> held(writer.transparentOrder().begin(), writer.transparentOrder().end());
  writer.sortTransparent({0.0, 0.0, -40.0});
  const std::vector<uint32_t> order(writer.transparentOrder().begin(), writer.transparentOrder().end());
  EXPECT_EQ(order, (std::vector<uint32_t>{1, 3}));
  const float opaqueMark = instances[0].model[3].z;
  instances[0].model[3].z = 99.0f;
  writer.writeTransparent(space, held, instances, commands);
  EXPECT_EQ(instances[0].model[3].z, 99.0f);
  EXPECT_NE(opaqueMark, 99.0f);
  EXPECT_EQ(instances[2].model[3], glm::vec4(-4.8125f, -4.8125f, -9.8125f, 1.0f));
  EXPECT_EQ(instances[3].model[3], glm::vec4(-4.8125f, -4.8125f, -34.8125f, 1.0f));
  EXPECT_EQ(instances[2].drawGroup, 1u);
  EXPECT_EQ(commands[1].firstInstance, 2u);
  EXPECT_EQ(commands[1].firstIndex, 30u);

  // A slot whose instance the copy already holds is not written again.
  instances[2].model[3].z = 77.0f;
  instances[3].model[3].z = 77.0f;
  writer.writeTransparent(space, std::vector<uint32_t>{1, 1}, instances, commands);
  EXPECT_EQ(instances[2].model[3].z, 77.0f);
  EXPECT_EQ(instances[3].model[3].z, -34.8125f);
}

// Many transparent instances, some at equal distances from the path: sorting the last frame's
// order again (InstanceWriter) gives drawOrder's stable sort from scratch at every position.
TEST(InstanceWriter, TransparentOrderIsDrawOrdersAtEveryCameraPosition) {
  scene::Scene s;
  s.meshes.resize(3);
  s.materials.resize(2);
  s.materials[1].alphaMode = scene::AlphaMode::Blend;
  for (uint32_t i = 0; i < 24; ++i) {
    scene::Instance instance;
    instance.mesh = i % 3;
    instance.material = i % 4 == 0 ? 0 : 1;
    // Pairs mirrored in x: equal distances from any camera on x = 0.
    const double x = (i % 2 == 0 ? 1.0 : -1.0) * double(i / 2 % 5);
    const double z = -3.0 * double(i / 2);
    instance.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0.0, z));
    instance.worldBounds = {{x - 0.5, -0.5, z - 0.5}, {x + 0.5, 0.5, z + 0.5}};
    s.instances.push_back(instance);
  }
  InstanceWriter writer(s);
  size_t reordered = 0;
  std::vector<uint32_t> last;
  for (int step = 0; step < 60; ++step) {
    const glm::dvec3 camera(step % 7 == 0 ? 0.0 : std::sin(step * 0.3) * 6.0, 1.0, 10.0 - 1.5 * step);
    writer.sortTransparent(camera);
    const DrawOrder expected = drawOrder(s, camera);
    const auto tail = std::span(expected.instanceOrder).subspan(expected.instanceOrder.size() - 18);
    const std::vector<uint32_t> order(writer.transparentOrder().begin(), writer.transparentOrder().end());
    ASSERT_EQ(order, std::vector<uint32_t>(tail.begin(), tail.end())) << "step " << step;
    reordered += order != last ? 1 : 0;
    last = order;
  }
  EXPECT_GT(reordered, 10u);  // the walk does reorder them
}

TEST(CopyContents, ACopyIsRewrittenWhollyOnlyWhenTheAnchorMovesAndPartlyWhenTheOrderDoes) {
  CopyContents copy;
  const RenderSpace here = RenderSpace::around({0.0, 0.0, 0.0});
  const RenderSpace there = RenderSpace::around({100.0, 0.0, 0.0});
  const std::vector<uint32_t> order{3, 1}, turned{1, 3};
  EXPECT_EQ(copy.compare(here, order), Write::Everything);  // a new copy holds nothing
  copy.hold(here, order);
  EXPECT_EQ(copy.compare(here, order), Write::Nothing);  // moved within the cell, same order
  EXPECT_EQ(copy.compare(here, turned), Write::Transparent);
  EXPECT_EQ(std::vector<uint32_t>(copy.transparent().begin(), copy.transparent().end()), order);  // until held
  copy.hold(here, turned);
  EXPECT_EQ(copy.compare(here, turned), Write::Nothing);
  EXPECT_EQ(copy.compare(there, turned), Write::Everything);
  copy.hold(there, turned);
  EXPECT_EQ(copy.compare(there, turned), Write::Nothing);
}

}  // namespace
}  // namespace fgb::render
