// Draw groups decide what each indirect command draws: opaque/masked instances of one mesh share
// a command, transparent instances get one each, sorted back to front.
#include "scene_workload/gpu_upload.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

namespace fgb::render {
namespace {

using features::DrawClass;

scene::Scene makeScene() {
  scene::Scene s;
  s.meshes.resize(2);
  s.materials.resize(3);
  s.materials[1].alphaMode = scene::AlphaMode::Mask;
  s.materials[2].alphaMode = scene::AlphaMode::Blend;
  auto add = [&](uint32_t mesh, uint32_t material, float z) {
    scene::Instance instance;
    instance.mesh = mesh;
    instance.material = material;
    instance.worldBounds = {{-1.0f, -1.0f, z - 1.0f}, {1.0f, 1.0f, z + 1.0f}};
    s.instances.push_back(instance);
  };
  add(0, 0, 0.0f);    // 0 opaque mesh 0
  add(1, 2, -5.0f);   // 1 transparent, near
  add(0, 0, -3.0f);   // 2 opaque mesh 0
  add(1, 2, -50.0f);  // 3 transparent, far
  add(1, 1, 0.0f);    // 4 masked mesh 1
  return s;
}

TEST(DrawGroups, GroupsSharedMeshesAndSortsTransparentBackToFront) {
  const auto s = makeScene();
  features::GpuScene gpu;
  DrawOrder order = drawOrder(s, glm::dvec3(0.0, 0.0, 10.0));
  gpu.groups = order.groups;
  gpu.instanceOrder = order.instanceOrder;
  ASSERT_EQ(gpu.groups.size(), 4u);  // opaque mesh 0, masked mesh 1, two transparent
  EXPECT_EQ(gpu.groups[0].drawClass, DrawClass::Opaque);
  EXPECT_EQ(gpu.groups[0].capacity, 2u);
  EXPECT_EQ(gpu.groups[1].drawClass, DrawClass::Masked);
  EXPECT_EQ(gpu.groups[2].drawClass, DrawClass::Transparent);
  // Farther transparent instance (3) first.
  EXPECT_EQ(gpu.instanceOrder[gpu.groups[2].firstSlot], 3u);
  EXPECT_EQ(gpu.instanceOrder[gpu.groups[3].firstSlot], 1u);
  // Slots are contiguous and cover every instance once.
  uint32_t expectedSlot = 0;
  for (const auto& group : gpu.groups) {
    EXPECT_EQ(group.firstSlot, expectedSlot);
    expectedSlot += group.capacity;
  }
  EXPECT_EQ(expectedSlot, s.instances.size());
  EXPECT_EQ(gpu.groupRange(DrawClass::Transparent), std::make_pair(2u, 2u));
  EXPECT_EQ(gpu.groupRange(DrawClass::Masked), std::make_pair(1u, 1u));
  // From the other end (a camera path's later frame) the transparent order turns around; the
  // groups' slots and sizes, which recorded commands use, stay.
  const DrawOrder behind = drawOrder(s, glm::dvec3(0.0, 0.0, -100.0));
  EXPECT_EQ(behind.instanceOrder[behind.groups[2].firstSlot], 1u);
  EXPECT_EQ(behind.instanceOrder[behind.groups[3].firstSlot], 3u);
  for (size_t g = 0; g < behind.groups.size(); ++g) {
    EXPECT_EQ(behind.groups[g].firstSlot, order.groups[g].firstSlot);
    EXPECT_EQ(behind.groups[g].capacity, order.groups[g].capacity);
  }
}

TEST(FrameConstants, ClusterGridCoversTheImageAndSlicesSpanNearToFar) {
  scene::Scene s;
  s.camera.nearPlane = 0.1f;
  s.camera.farPlane = 100.0f;
  features::RenderSettings settings;
  settings.width = 330;
  settings.height = 170;
  settings.clusterSlices = 24;
  const auto c = makeFrameConstants(s, s.camera, settings);
  EXPECT_EQ(c.clusterGrid.x, 21u);  // ceil(330 / 16)
  EXPECT_EQ(c.clusterGrid.y, 11u);
  // slice(z) = log(z) * scale + bias: 0 at near, slices at far.
  EXPECT_NEAR(std::log(0.1f) * c.depthRange.z + c.depthRange.w, 0.0f, 1e-4f);
  EXPECT_NEAR(std::log(100.0f) * c.depthRange.z + c.depthRange.w, 24.0f, 1e-3f);
  // Y is flipped so that +Y world maps to the top of the image (negative clip Y).
  // A scene without a camera path anchors render space at its camera (render_space.hpp).
  EXPECT_EQ(c.cameraPosition, glm::vec4(0, 0, 0, 1));
  const glm::vec4 up = c.viewProj * glm::vec4(glm::vec3(s.camera.target - s.camera.position) + glm::vec3(0, 1, 0), 1.0f);
  EXPECT_LT(up.y, 0.0f);
}

TEST(FrameConstants, InfiniteFarSlicesClustersUpToTheSceneAndFarFromTheOriginNothingIsLarge) {
  scene::Scene s = makeScene();
  const glm::dvec3 offset(1e7, 0.0, 1e7);
  for (auto& instance : s.instances) instance.worldBounds = {instance.worldBounds.min + offset, instance.worldBounds.max + offset};
  s.camera.position = offset + glm::dvec3(0, 0, 10);
  s.camera.target = offset;
  s.camera.nearPlane = 1e-4f;
  s.camera.farPlane = std::numeric_limits<float>::infinity();
  features::RenderSettings settings;
  const auto c = makeFrameConstants(s, s.camera, settings);
  // The farthest box corner is ~61 m away (instance 3 spans z -51..-49 around the offset).
  EXPECT_GT(c.depthRange.y, 60.0f);
  EXPECT_LT(c.depthRange.y, 62.0f);
  EXPECT_TRUE(std::isfinite(c.depthRange.z) && std::isfinite(c.depthRange.w));
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) EXPECT_LT(std::abs(c.viewProj[column][row]), 10.0f) << column << "," << row;
}

}  // namespace
}  // namespace fgb::render
