// Render paths as data (scene_workload/render_paths.cpp): the built-in paths from the embedded
// table, and the one-line InputError for each way a path file can be wrong (no GPU).
#include "features/feature_registry.hpp"
#include "scene_workload/render_paths.hpp"

#include <gtest/gtest.h>

#include <fgb/core/error.hpp>

namespace fgb::render {
namespace {

using features::DebugView;
using features::DepthTest;
using features::PostPassForm;

std::string errorOf(const std::string& text, const std::string& source = "my.json") {
  try {
    (void)parseRenderPath(text, source);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

// A valid forward-like path with `features` as its feature list (JSON array text).
std::string pathWith(const std::string& features, const std::string& more = "") {
  return R"({"name": "test", "features": )" + features + more + "}";
}

constexpr const char* kForwardFeatures =
    R"([{"feature": "clustered_lighting"}, {"feature": "meshes"}, {"feature": "particles"},
        {"feature": "msaa_resolve"}, {"feature": "ssaa_resolve"}, {"feature": "bloom"},
        {"feature": "exposure"}, {"feature": "tonemap"}])";

TEST(RenderPath, BuiltInPathsAreEmbeddedAndHoldEveryDecision) {
  std::vector<std::string> names;
  for (const auto& builtin : features::builtinRenderPaths()) names.emplace_back(builtin.name);
  EXPECT_EQ(names, (std::vector<std::string>{"forward", "meshlet", "visbuffer"}));

  const auto forward = loadRenderPath("forward");
  EXPECT_EQ(forward.name, "forward");
  EXPECT_EQ(forward.post, PostPassForm::Fragment);
  EXPECT_EQ(forward.depthTest, DepthTest::Attachment);
  EXPECT_EQ(forward.maxMsaa, 8u);
  EXPECT_FALSE(forward.uploadClusters);
  EXPECT_FALSE(forward.has("visbuffer"));
  ASSERT_EQ(forward.features.size(), 8u);
  EXPECT_EQ(forward.features[1].feature, "meshes");
  EXPECT_TRUE(forward.features[1].options.at("opaque").get<bool>());

  const auto vis = loadRenderPath("visbuffer");
  EXPECT_EQ(vis.post, PostPassForm::Compute);
  EXPECT_EQ(vis.depthTest, DepthTest::OpaqueDepthBuffer);
  EXPECT_EQ(vis.maxMsaa, 1u);
  EXPECT_TRUE(vis.uploadClusters);
  EXPECT_TRUE(vis.has("visbuffer"));
  EXPECT_FALSE(vis.features[2].options.at("opaque").get<bool>());

  // The plan: the features in the file's order, and what the frame's images need.
  const auto plan = planRenderPath(vis);
  ASSERT_EQ(plan.features.size(), 9u);
  EXPECT_EQ(plan.features[1]->name(), "visbuffer");
  EXPECT_TRUE(plan.computeWritesHdr);
  EXPECT_TRUE(plan.computeWritesDisplay);
  const auto forwardPlan = planRenderPath(forward);
  EXPECT_FALSE(forwardPlan.computeWritesHdr);
  EXPECT_FALSE(forwardPlan.computeWritesDisplay);
  EXPECT_EQ(forwardPlan.displayFormat, features::kDisplayFormat);

  // The mesh-shader path: forward's depth attachment, MSAA and fragment post passes, the clusters
  // uploaded, its feature drawing the opaque scene before forward's transparent meshes.
  const auto meshlet = loadRenderPath("meshlet");
  EXPECT_EQ(meshlet.post, PostPassForm::Fragment);
  EXPECT_EQ(meshlet.depthTest, DepthTest::Attachment);
  EXPECT_EQ(meshlet.maxMsaa, 8u);
  EXPECT_TRUE(meshlet.uploadClusters);
  const auto meshletPlan = planRenderPath(meshlet);
  ASSERT_EQ(meshletPlan.features.size(), 9u);
  EXPECT_EQ(meshletPlan.features[1]->name(), "meshlets");
  EXPECT_EQ(meshletPlan.features[2]->name(), "meshes");
  EXPECT_FALSE(meshletPlan.computeWritesHdr);
}

TEST(RenderPath, DefaultsAreTheForwardPathsAndMaxMsaaTheFeaturesLimit) {
  const auto path = parseRenderPath(pathWith(kForwardFeatures), "my.json");
  EXPECT_EQ(path.source, "my.json");
  EXPECT_EQ(path.post, PostPassForm::Fragment);
  EXPECT_EQ(path.maxMsaa, 8u);
  EXPECT_TRUE(path.features[1].options.at("opaque").get<bool>());  // the option's default
  EXPECT_EQ(renderPathOf({}).name, "forward");
}

TEST(RenderPath, ClusterDebugViewsNeedAPathThatDrawsClusters) {
  EXPECT_NO_THROW(checkRenderPathSettings(loadRenderPath("visbuffer"), 1, DebugView::Lod));
  EXPECT_NO_THROW(checkRenderPathSettings(loadRenderPath("meshlet"), 1, DebugView::Clusters));
  EXPECT_NO_THROW(checkRenderPathSettings(loadRenderPath("forward"), 1, DebugView::LightComplexity));
  try {
    checkRenderPathSettings(loadRenderPath("forward"), 1, DebugView::Clusters);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "--set debug.view=clusters: render.path=forward draws no clusters (they colour the "
                 "clusters that render.path=visbuffer and meshlet draw)");
  }
}

TEST(RenderPath, MsaaAboveTheMaxIsRefusedNamingSupersampling) {
  const auto vis = loadRenderPath("visbuffer");
  EXPECT_NO_THROW(checkRenderPathSettings(vis, 1, DebugView::None));
  try {
    checkRenderPathSettings(vis, 4, DebugView::None);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "--msaa 4: render.path=visbuffer draws at most 1 sample(s) per pixel (its max_msaa); use --set "
                 "render.ssaa=N for anti-aliasing");
  }
}

TEST(RenderPath, BadFilesSayWhatIsWrongOnOneLine) {
  const std::string forward = kForwardFeatures;
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = forward;
    text.replace(text.find(from), from.size(), to);
    return pathWith(text);
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{", "--set render.path=my.json: not valid JSON: "},
      {pathWith(kForwardFeatures, R"(, "colour": 1)"),
       R"(--set render.path=my.json: unknown field "colour" (known: name, description, features, post, depth_test, max_msaa, upload))"},
      {replaced(R"("feature": "bloom")", R"("feature": "blom")"),
       R"(--set render.path=my.json: features[5]: unknown feature "blom" (known: bloom, clustered_lighting, exposure, meshes, meshlets, msaa_resolve, particles, ssaa_resolve, tonemap, visbuffer))"},
      {replaced(R"({"feature": "meshes"})", R"({"feature": "meshes", "options": {"opaq": true}})"),
       R"(--set render.path=my.json: features[1] "meshes": unknown option "opaq" (known: opaque, lod, transparent))"},
      {replaced(R"({"feature": "bloom"})", R"({"feature": "bloom", "options": {"mips": 3}})"),
       R"(--set render.path=my.json: features[5] "bloom": unknown option "mips" (the feature has no options))"},
      {replaced(R"({"feature": "meshes"})", R"({"feature": "meshes", "options": {"opaque": 0}})"),
       R"(--set render.path=my.json: features[1] "meshes": option "opaque": 0 is not a boolean like its default true)"},
      // Without the opaque meshes, nothing writes the depth attachment the particles test against.
      {replaced(R"({"feature": "meshes"})", R"({"feature": "meshes", "options": {"opaque": false}})"),
       R"(--set render.path=my.json: features[1] "meshes": needs depth_attachment, which no entry before it provides (depth_attachment comes from meshes with "opaque": true, or meshlets; available here: light_lists))"},
      // The visibility buffer has one sample per pixel ...
      {pathWith(R"([{"feature": "visbuffer"}, {"feature": "meshes", "options": {"opaque": false}},
                    {"feature": "msaa_resolve"}, {"feature": "ssaa_resolve"}, {"feature": "tonemap"}])",
                R"(, "max_msaa": 8, "depth_test": "opaque_depth_buffer", "upload": {"clusters": true})"),
       R"(--set render.path=my.json: features[0] "visbuffer": draws at most 1 sample(s) per pixel, but "max_msaa" is 8)"},
      // ... and needs its clusters uploaded.
      {pathWith(R"([{"feature": "visbuffer"}, {"feature": "meshes", "options": {"opaque": false}},
                    {"feature": "msaa_resolve"}, {"feature": "ssaa_resolve"}, {"feature": "tonemap"}])",
                R"(, "max_msaa": 1, "depth_test": "opaque_depth_buffer")"),
       R"(--set render.path=my.json: features[0] "visbuffer": needs clusters, which no entry before it provides (clusters comes from "upload": {"clusters": true}; available here: nothing))"},
      // Two features drawing the opaque scene.
      {pathWith(R"([{"feature": "visbuffer"}, {"feature": "meshes"}, {"feature": "msaa_resolve"},
                    {"feature": "ssaa_resolve"}, {"feature": "tonemap"}])",
                R"(, "max_msaa": 1, "upload": {"clusters": true})"),
       R"(--set render.path=my.json: features[1] "meshes": provides opaque_scene, which features[0] "visbuffer" already does)"},
      // Tone mapping reads the output HDR image the SSAA resolve writes.
      {replaced(R"({"feature": "ssaa_resolve"}, )", ""),
       R"(--set render.path=my.json: features[4] "bloom": needs output_hdr, which no entry before it provides (output_hdr comes from ssaa_resolve; available here: depth_attachment, hdr, light_lists, opaque_scene))"},
      {replaced(R"({"feature": "tonemap"})", R"({"feature": "tonemap"}, {"feature": "particles"})"),
       R"(--set render.path=my.json: features[8] "particles": given twice (also features[2]))"},
      {pathWith(R"([{"feature": "meshes"}, {"feature": "msaa_resolve"}, {"feature": "ssaa_resolve"},
                    {"feature": "tonemap"}, {"feature": "particles"}])"),
       R"(--set render.path=my.json: features[4] "particles": a scene colour feature after features[3] "tonemap" (tone mapping); the order is lighting, opaque, scene colour, msaa resolve, ssaa resolve, bloom, exposure, tone mapping)"},
      {replaced(R"(, {"feature": "tonemap"})", ""),
       R"(--set render.path=my.json: no entry provides display, which every path needs (it comes from tonemap; the path provides: bloom, depth_attachment, hdr, light_lists, opaque_scene, output_hdr))"},
      // The meshes option "transparent" is a word of its own.
      {pathWith(R"([{"feature": "meshes", "options": {"transparent": "sorted"}}, {"feature": "msaa_resolve"},
                    {"feature": "ssaa_resolve"}, {"feature": "tonemap"}])"),
       R"(--set render.path=my.json: the meshes option "transparent" is "sorted", not raster or compute)"},
      {pathWith(kForwardFeatures, R"(, "post": "vertex")"),
       R"(--set render.path=my.json: "post": "vertex" is not one of fragment, compute)"},
      {pathWith(kForwardFeatures, R"(, "max_msaa": 3)"),
       R"(--set render.path=my.json: "max_msaa": 3 is not one of 1, 2, 4, 8)"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = errorOf(text);
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    if (expected.ends_with(": ")) {
      EXPECT_TRUE(message.starts_with(expected)) << message;
    } else {
      EXPECT_EQ(message, expected);
    }
  }
}

TEST(RenderPath, AFileThatCannotBeReadOrIsNotJsonIsNamed) {
  try {
    (void)loadRenderPath("no/such/path.json");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "--set render.path=no/such/path.json: cannot read the file (a built-in path is one of forward, meshlet, "
                 "visbuffer)");
  }
}

TEST(RenderPath, EveryRegisteredFeatureHasAFactoryAndAContract) {
  for (const auto& kind : features::featureKinds()) {
    nlohmann::json options = nlohmann::json::object();
    for (const auto& option : kind.options) options[option.name] = option.defaultValue;
    EXPECT_NE(kind.create(options), nullptr) << kind.name;
    (void)kind.contract(options, features::RenderPath{});
  }
}

}  // namespace
}  // namespace fgb::render
