#include <gtest/gtest.h>

#include <fgb/core/error.hpp>
#include <fgb/core/knob_registry.hpp>
#include <limits>
#include <stdexcept>

namespace fgb {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

KnobRegistry twoLayers() {
  KnobRegistry registry;
  using enum ReferenceRole;
  registry.add({{"render.ssaa", KnobType::Integer, 1, 4, false, false, {}, "renderer", "", Approximation, "4"},
                {"lighting.mode",
                 KnobType::Word,
                 0,
                 0,
                 false,
                 false,
                 {"clustered", "all"},
                 "renderer",
                 "",
                 Approximation,
                 "all"}});
  registry.add({{"camera.near", KnobType::Number, 0, kInf, true, false, {}, "scene", "", Content, ""},
                {"camera.far", KnobType::Number, 0, kInf, true, false, {"inf"}, "scene", "", Content, ""},
                {"camera.fov", KnobType::Number, 0, 179, true, true, {}, "scene", "", Content, ""},
                {"camera.position", KnobType::Vec3, -kInf, kInf, false, false, {}, "scene", "", Content, ""},
                {"post.bloom", KnobType::Flag, 0, 0, false, false, {}, "scene", "", Look, ""}});
  return registry;
}

std::string messageOf(const KnobRegistry& registry, const std::string& key, const std::string& value) {
  try {
    registry.check(key, value);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(KnobRegistry, AcceptsEveryValidValue) {
  const KnobRegistry registry = twoLayers();
  EXPECT_NO_THROW(registry.checkAll({{"render.ssaa", "1"},
                                     {"lighting.mode", "all"},
                                     {"camera.near", "1e-6"},
                                     {"camera.far", "inf"},
                                     {"camera.fov", "170"},
                                     {"camera.position", "1,-2.5,3e7"},
                                     {"post.bloom", "off"}}));
  EXPECT_NO_THROW(registry.check("render.ssaa", "4"));
}

TEST(KnobRegistry, UnknownKeyNamesItAndListsTheKnownOnesOnOneLine) {
  const KnobRegistry registry = twoLayers();
  const std::string message = messageOf(registry, "foo.bar", "1");
  EXPECT_NE(message.find("--set foo.bar=1"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown knob 'foo.bar'"), std::string::npos) << message;
  EXPECT_NE(
      message.find("camera.far, camera.fov, camera.near, camera.position, lighting.mode, post.bloom, render.ssaa"),
      std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  // A key under an owned prefix is no more known than one under a prefix nobody owns.
  EXPECT_NE(messageOf(registry, "render.ssa", "2").find("unknown knob 'render.ssa'"), std::string::npos);
}

TEST(KnobRegistry, OutOfRangeAndMalformedValuesSayWhatWasExpected) {
  const KnobRegistry registry = twoLayers();
  EXPECT_EQ(messageOf(registry, "render.ssaa", "5"), "--set render.ssaa=5: expected an integer in [1, 4]");
  EXPECT_EQ(messageOf(registry, "render.ssaa", "0"), "--set render.ssaa=0: expected an integer in [1, 4]");
  EXPECT_EQ(messageOf(registry, "render.ssaa", "2.5"), "--set render.ssaa=2.5: expected an integer in [1, 4]");
  EXPECT_EQ(messageOf(registry, "lighting.mode", "some"), "--set lighting.mode=some: expected clustered|all");
  EXPECT_EQ(messageOf(registry, "camera.near", "0"), "--set camera.near=0: expected a finite number > 0");
  EXPECT_EQ(messageOf(registry, "camera.far", "-1"), "--set camera.far=-1: expected a finite number > 0 or inf");
  EXPECT_EQ(messageOf(registry, "camera.fov", "179"), "--set camera.fov=179: expected a finite number in (0, 179)");
  EXPECT_EQ(messageOf(registry, "camera.near", "nan"), "--set camera.near=nan: expected a finite number > 0");
  EXPECT_EQ(messageOf(registry, "camera.position", "1,2"), "--set camera.position=1,2: expected three numbers x,y,z");
  EXPECT_EQ(messageOf(registry, "camera.position", "1,2,3,4"),
            "--set camera.position=1,2,3,4: expected three numbers x,y,z");
  EXPECT_EQ(messageOf(registry, "post.bloom", "yes"), "--set post.bloom=yes: expected 0|1|true|false|on|off");
  EXPECT_EQ(messageOf(registry, "render.ssaa", ""), "--set render.ssaa=: expected an integer in [1, 4]");
}

// A word-or-file knob (render.path): one of its words, or a user's FILE.json, read and checked by
// its owner when used.
TEST(KnobRegistry, AWordOrFileKnobTakesItsWordsOrAJsonFile) {
  KnobRegistry registry;
  registry.add({{"render.path", KnobType::WordOrFile, 0, 0, false, false, {"forward", "visbuffer"}, "renderer", "",
                 ReferenceRole::CostOnly, "forward"}});
  EXPECT_NO_THROW(registry.check("render.path", "visbuffer"));
  EXPECT_NO_THROW(registry.check("render.path", "bench/paths/forward-no-bloom.json"));
  EXPECT_EQ(messageOf(registry, "render.path", "deferred"),
            "--set render.path=deferred: expected forward|visbuffer or FILE.json");
  EXPECT_EQ(messageOf(registry, "render.path", ".json"), "--set render.path=.json: expected forward|visbuffer or FILE.json");
}

// One parser per type checks and converts: layers take the value in its type, never the text.
TEST(KnobRegistry, ParsesEachValueOnceIntoItsType) {
  const KnobRegistry registry = twoLayers();
  EXPECT_EQ(std::get<double>(registry.parse("render.ssaa", "3")), 3.0);
  EXPECT_EQ(std::get<std::string>(registry.parse("lighting.mode", "all")), "all");
  EXPECT_EQ(std::get<double>(registry.parse("camera.near", "1e-6")), 1e-6);
  EXPECT_EQ(std::get<std::string>(registry.parse("camera.far", "inf")), "inf");  // one of its words
  EXPECT_EQ(std::get<KnobVec3>(registry.parse("camera.position", "1,-2.5,3e7")), (KnobVec3{1.0, -2.5, 3e7}));
  EXPECT_FALSE(std::get<bool>(registry.parse("post.bloom", "off")));
  EXPECT_TRUE(std::get<bool>(registry.parse("post.bloom", "1")));
  EXPECT_THROW((void)registry.parse("render.ssaa", "5"), InputError);
  EXPECT_FALSE(tryParseKnobValue(*registry.find("camera.position"), "1,2").has_value());
}

TEST(KnobRegistry, AKeyRegisteredTwiceIsAProgrammingError) {
  KnobRegistry registry = twoLayers();
  EXPECT_THROW(
      registry.add(
          {{"render.ssaa", KnobType::Integer, 1, 2, false, false, {}, "other", "", ReferenceRole::Content, ""}}),
      std::logic_error);
}

TEST(KnobRegistry, SplitsAssignmentsAndRejectsOnesWithoutAKey) {
  const auto knobs = splitKnobAssignments({"a.b=1", "c.d=x=y", "a.b=2"});
  EXPECT_EQ(knobs.at("a.b"), "2");  // the later assignment wins
  EXPECT_EQ(knobs.at("c.d"), "x=y");
  EXPECT_THROW(splitKnobAssignments({"novalue"}), InputError);
  EXPECT_THROW(splitKnobAssignments({"=1"}), InputError);
}

// Issue 30: the sweep's reference reads each knob's role from its registry entry, so a knob added
// without one (or an approximation without the value at which it is exact) must not register.
TEST(KnobRegistry, RefusesAKnobWithoutAReferenceRole) {
  KnobRegistry registry;
  EXPECT_THROW(
      registry.add(
          {{"render.new_knob", KnobType::Flag, 0, 0, false, false, {}, "renderer", "", ReferenceRole::Unset, ""}}),
      std::logic_error);
  EXPECT_THROW(registry.add({{"render.ssaa",
                              KnobType::Integer,
                              1,
                              4,
                              false,
                              false,
                              {},
                              "renderer",
                              "",
                              ReferenceRole::Approximation,
                              "9"}}),
               std::logic_error);
  EXPECT_NO_THROW(registry.add(
      {{"render.ok", KnobType::Flag, 0, 0, false, false, {}, "renderer", "", ReferenceRole::CostOnly, "0"}}));
  EXPECT_EQ(registry.find("render.ok")->role, ReferenceRole::CostOnly);
  EXPECT_STREQ(referenceRoleName(ReferenceRole::Look), "look");
}

}  // namespace
}  // namespace fgb
