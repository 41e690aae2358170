// The CPU frustum test: the reference for the GPU cull.
#include <fgb/scene/frustum.hpp>

#include <gtest/gtest.h>

#include <limits>

using namespace fgb::scene;

namespace {

Camera lookingDownMinusZ() {
  Camera c;
  c.position = {0, 0, 0};
  c.target = {0, 0, -1};
  c.verticalFovDeg = 90.0f;
  c.nearPlane = 0.1f;
  c.farPlane = 100.0f;
  return c;
}

Aabb boxAt(glm::vec3 centre, float half = 0.5f) { return {centre - half, centre + half}; }

}  // namespace

TEST(Frustum, BoxesInFrontAreVisibleBehindAndBeyondAreNot) {
  const Frustum f = Frustum::fromCamera(lookingDownMinusZ(), 1.0f);
  EXPECT_TRUE(f.intersects(boxAt({0, 0, -10})));
  EXPECT_FALSE(f.intersects(boxAt({0, 0, 10})));         // behind
  EXPECT_FALSE(f.intersects(boxAt({0, 0, -200})));       // past far
  EXPECT_FALSE(f.intersects(boxAt({0, 0, -0.01f}, 0.005f)));  // before near
  EXPECT_FALSE(f.intersects(boxAt({30, 0, -10})));       // right of the 45-degree half angle
  EXPECT_TRUE(f.intersects(boxAt({10.4f, 0, -10})));     // straddles the right plane
  EXPECT_FALSE(f.intersects(boxAt({0, -30, -10})));      // below
  EXPECT_FALSE(f.intersects(Aabb::empty()));
}

TEST(Frustum, AspectWidensHorizontally) {
  const Camera c = lookingDownMinusZ();
  const Aabb wide = boxAt({15, 0, -10});
  EXPECT_FALSE(Frustum::fromCamera(c, 1.0f).intersects(wide));
  EXPECT_TRUE(Frustum::fromCamera(c, 2.0f).intersects(wide));
}

TEST(Frustum, CountVisibleSumsTriangles) {
  Scene scene;
  scene.meshes.push_back(Mesh{"m", 0, 3, 0, 3, {{-1, -1, -1}, {1, 1, 1}}});
  for (float z : {-10.0f, 10.0f, -20.0f}) {
    Instance i;
    i.worldBounds = boxAt({0, 0, z}, 1.0f);
    scene.instances.push_back(i);
  }
  const Visibility v = countVisible(scene, lookingDownMinusZ(), 1.0f);
  EXPECT_EQ(v.instances, 2u);
  EXPECT_EQ(v.triangles, 2u);
}

TEST(Projection, ReversedZMapsNearToOneAndFarToZero) {
  Camera c = lookingDownMinusZ();
  auto depthAt = [&](double distance) {
    const glm::vec4 clip = projectionMatrix(c, 1.0f) * glm::vec4(0.0f, 0.0f, float(-distance), 1.0f);
    return clip.z / clip.w;
  };
  EXPECT_NEAR(depthAt(0.1), 1.0f, 1e-6f);
  EXPECT_NEAR(depthAt(100.0), 0.0f, 1e-6f);
  EXPECT_GT(depthAt(1.0), depthAt(2.0));  // nearer is greater
  c.farPlane = std::numeric_limits<float>::infinity();
  EXPECT_NEAR(depthAt(0.1), 1.0f, 1e-6f);
  EXPECT_NEAR(depthAt(1e5), 1e-6f, 1e-9f);  // near / d: never reaches 0
  const Frustum f = Frustum::fromCamera(c, 1.0f);
  EXPECT_TRUE(f.intersects(boxAt({0, 0, -1e6f})));  // nothing is past an infinite far plane
  EXPECT_FALSE(f.intersects(boxAt({0, 0, -0.01f}, 0.005f)));
}

TEST(Frustum, CameraRelativeCullingDoesNotDependOnTheDistanceFromTheOrigin) {
  Scene scene;
  scene.meshes.push_back(Mesh{"m", 0, 3, 0, 3, {{-1, -1, -1}, {1, 1, 1}}});
  // 1 cm boxes just inside and just outside the 45-degree right plane (x = 10 at z = -10).
  for (double x : {9.99, 10.02}) {
    Instance i;
    i.worldBounds = boxAt({float(x), 0, -10}, 0.005f);
    scene.instances.push_back(i);
  }
  Camera camera = lookingDownMinusZ();
  const Visibility atOrigin = countVisible(scene, camera, 1.0f);
  const glm::dvec3 offset(1e7, 0.0, -1e7);  // float steps by 1 m out there
  for (Instance& i : scene.instances) i.worldBounds = Aabb{i.worldBounds.min + offset, i.worldBounds.max + offset};
  camera.position += offset;
  camera.target += offset;
  EXPECT_EQ(atOrigin.instances, 1u);
  EXPECT_EQ(countVisible(scene, camera, 1.0f).instances, atOrigin.instances);
  const glm::mat4 view = viewMatrix(camera);
  EXPECT_EQ(view[3], glm::vec4(0, 0, 0, 1));  // camera-relative: no translation
}
