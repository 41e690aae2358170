// Scene file parsing and knobs: errors name the file, the field and what was expected.
#include <fgb/core/error.hpp>
#include <fgb/scene/knobs.hpp>
#include <fgb/scene/scene_file.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace fgb::scene;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

std::string errorOf(const std::string& text) {
  try {
    parseSceneText(text, "scenes/x.json");
  } catch (const fgb::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(SceneFile, ParsesEveryKnownSection) {
  const SceneDescription d = parseSceneText(R"({
    "name": "demo",
    "generator": {"type": "atrium", "scale": 0.5},
    "models": [{"file": "m/a.gltf", "position": [1, 2, 3], "scale": 2}, "b.obj"],
    "camera": {"position": [0, 1, 5], "target": [0, 1, 0], "fov_deg": 50},
    "lights": [{"position": [1, 2, 3], "color": [1, 0, 0], "intensity": 4, "radius": 5}],
    "sun": {"direction": [0, -2, 0], "intensity": 1.5},
    "emitters": [{"position": [0, 1, 0], "rate": 10, "speed": [1, 2]}],
    "post": {"exposure": 0.8, "bloom": {"threshold": 2}},
    "render": {"msaa": 8}
  })", "/data/scenes/demo.json");
  EXPECT_EQ(d.name, "demo");
  ASSERT_TRUE(d.generator);
  EXPECT_EQ(d.generator->type, "atrium");
  EXPECT_EQ(d.generator->params.at("scale"), 0.5);
  ASSERT_EQ(d.models.size(), 2u);
  EXPECT_EQ(d.models[0].file, std::filesystem::path("/data/scenes/m/a.gltf"));
  EXPECT_FLOAT_EQ(d.models[0].placement[3][1], 2.0f);
  EXPECT_FLOAT_EQ(d.models[0].placement[0][0], 2.0f);
  EXPECT_EQ(d.models[1].file, std::filesystem::path("/data/scenes/b.obj"));
  ASSERT_EQ(d.lights.size(), 1u);
  EXPECT_FLOAT_EQ(d.lights[0].radius, 5.0f);
  ASSERT_TRUE(d.sun);
  EXPECT_FLOAT_EQ(d.sun->direction.y, -1.0f);
  ASSERT_EQ(d.emitters.size(), 1u);
  EXPECT_FLOAT_EQ(d.emitters[0].speedMax, 2.0f);
  EXPECT_EQ(d.renderer.at("render").at("msaa"), 8);
  PostSettings post;
  applyPostOverrides(post, d.post, "x");
  EXPECT_FLOAT_EQ(post.exposure, 0.8f);
  EXPECT_FLOAT_EQ(post.bloom.threshold, 2.0f);
}

TEST(SceneFile, EmptyObjectIsAnEmptyScene) {
  const SceneDescription d = parseSceneText("{}", "scenes/empty.json");
  EXPECT_EQ(d.name, "empty");
  EXPECT_FALSE(d.generator);
  EXPECT_TRUE(d.models.empty());
}

TEST(SceneFile, ErrorsNameFileFieldAndExpectation) {
  EXPECT_THAT(errorOf(R"({"lights": [{"position": [1, 2]}]})"),
              AllOf(HasSubstr("scenes/x.json"), HasSubstr("lights[0].position"), HasSubstr("3 numbers")));
  EXPECT_THAT(errorOf(R"({"camera": {"fov_deg": "wide"}})"),
              AllOf(HasSubstr("camera.fov_deg"), HasSubstr("expected a number"), HasSubstr("string")));
  EXPECT_THAT(errorOf(R"({"camera": {"near": 10, "far": 1}})"), HasSubstr("camera.far"));
  EXPECT_THAT(errorOf(R"({"lights": [{"position": [0,0,0], "colour": [1,1,1]}]})"),
              AllOf(HasSubstr("lights[0].colour"), HasSubstr("unknown field")));
  EXPECT_THAT(errorOf(R"({"modle": "a.obj"})"), AllOf(HasSubstr("'modle'"), HasSubstr("unknown field")));
  EXPECT_THAT(errorOf(R"({"generator": {"scale": 2}})"), HasSubstr("generator.type"));
  EXPECT_THAT(errorOf(R"({"emitters": [{"position": [0,0,0], "speed": [3, 1]}]})"), HasSubstr("emitters[0].speed"));
  EXPECT_THAT(errorOf("{ \"name\": "), AllOf(HasSubstr("scenes/x.json"), HasSubstr("not valid JSON")));
  EXPECT_THAT(errorOf("[1, 2]"), HasSubstr("expected an object"));
}

TEST(SceneFile, ExtensionKeysPassThrough) {
  EXPECT_NO_THROW(parseSceneText(R"({"x-note": 1, "_comment": "hi", "budget": "b.json"})", "s.json"));
}

TEST(SceneFile, MissingFileIsInputError) {
  EXPECT_THROW(parseSceneFile("/nonexistent/scene.json"), fgb::InputError);
}

TEST(Knobs, OwnedKeysAreValidatedOthersIgnored) {
  const Knobs knobs = Knobs::parse({"atrium.scale=2", "camera.position=1,2,3", "bloom.passes=4", "msaa=8"});
  EXPECT_EQ(knobs.number("atrium.scale"), 2.0);
  EXPECT_EQ(knobs.vec3("camera.position"), glm::dvec3(1, 2, 3));
  EXPECT_FALSE(knobs.has("bloom.passes"));
  try {
    Knobs::parse({"atrium.sclae=2"});
    FAIL();
  } catch (const fgb::InputError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("atrium.sclae"), HasSubstr("unknown knob"), HasSubstr("atrium.scale")));
  }
  // Out of range (from knobSpecs()): one line saying what was expected.
  try {
    Knobs::parse({"camera.fov=200"});
    FAIL();
  } catch (const fgb::InputError& e) {
    EXPECT_STREQ(e.what(), "--set camera.fov=200: expected a finite number in (0, 179)");
  }
  EXPECT_THROW(Knobs::parse({"camera.near=0"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"atrium.texture_size=2"}), fgb::InputError);
  for (const fgb::KnobSpec& spec : knobSpecs()) EXPECT_EQ(spec.owner, "scene") << spec.key;
  EXPECT_THROW(Knobs::parse({"atrium.scale=big"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"camera.position=1,2"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"scene.lights=maybe"}), fgb::InputError);
  EXPECT_THROW(Knobs::parse({"noequals"}), fgb::InputError);
}

TEST(SceneFile, CameraFarMayBeInfinite) {
  const SceneDescription d = parseSceneText(R"({"generator": {"type": "atrium"}, "camera": {"far": "inf"}})", "x.json");
  Camera camera;
  applyCameraOverrides(camera, d.camera, "x.json");
  EXPECT_TRUE(std::isinf(camera.farPlane));
  EXPECT_THROW(parseSceneText(R"({"generator": {"type": "atrium"}, "camera": {"far": "far"}})", "x.json"),
               fgb::InputError);
}

TEST(Knobs, WordsAndScalesOfTheStabilityKnobs) {
  const Knobs knobs = Knobs::parse({"camera.far=inf", "post.exposure=auto", "scene.light_scale=1e6"});
  EXPECT_TRUE(knobs.isWord("camera.far", "inf"));
  EXPECT_EQ(knobs.numberOr("camera.far", "inf"), std::nullopt);
  EXPECT_TRUE(knobs.isWord("post.exposure", "auto"));
  EXPECT_EQ(knobs.scale("scene.light_scale"), 1e6);
  EXPECT_EQ(Knobs::parse({"camera.far=500"}).numberOr("camera.far", "inf"), 500.0);
  for (const char* bad : {"camera.far=infinite", "post.exposure=automatic", "scene.light_scale=0",
                          "scene.light_scale=-2", "scene.emissive_scale=1e13", "scene.light_scale=x"}) {
    EXPECT_THROW(Knobs::parse({bad}), fgb::InputError) << bad;
  }
}
