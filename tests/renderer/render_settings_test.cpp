#include "features/context/render_settings.hpp"

#include <gtest/gtest.h>

#include <fgb/core/error.hpp>
#include <fgb/scene/knobs.hpp>

namespace fgb::features {
namespace {

TEST(RenderSettings, AppliesRendererKnobsAndIgnoresOthers) {
  RenderSettings settings;
  applyRendererKnobs(settings, {{"debug.view", "light-complexity"},
                                {"render.depth_prepass", "1"},
                                {"lighting.slices", "16"},
                                {"post.exposure", "2"}});
  EXPECT_EQ(settings.debugView, DebugView::LightComplexity);
  EXPECT_TRUE(settings.depthPrepass);
  EXPECT_EQ(settings.clusterSlices, 16u);
}

TEST(RenderSettings, RejectsMalformedValuesNamingTheKey) {
  RenderSettings settings;
  try {
    applyRendererKnobs(settings, {{"debug.view", "heat"}});
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("debug.view=heat"), std::string::npos) << error.what();
  }
  EXPECT_THROW(applyRendererKnobs(settings, {{"lighting.slices", "0"}}), InputError);
  EXPECT_THROW(applyRendererKnobs(settings, {{"lighting.slices", "12x"}}), InputError);
}

TEST(RenderSettings, RejectsUnknownKeysUnderItsPrefixes) {
  RenderSettings settings;
  EXPECT_THROW(applyRendererKnobs(settings, {{"debug.veiw", "none"}}), InputError);
  EXPECT_THROW(applyRendererKnobs(settings, {{"bloom.mip", "3"}}), InputError);
  EXPECT_NO_THROW(applyRendererKnobs(settings, {{"atrium.scale", "0.5"}, {"harness.x", "1"}}));
}

// render.path is the path itself (tests/renderer/render_path_test.cpp), not a setting: the registry
// takes a built-in name or a FILE.json and refuses other words naming both.
TEST(RenderSettings, RenderPathTakesABuiltInNameOrAJsonFile) {
  RenderSettings settings;
  EXPECT_NO_THROW(applyRendererKnobs(settings, {{"render.path", "visbuffer"}}));
  EXPECT_NO_THROW(applyRendererKnobs(settings, {{"render.path", "forward"}}));
  EXPECT_NO_THROW(applyRendererKnobs(settings, {{"render.path", "meshlet"}}));
  EXPECT_NO_THROW(applyRendererKnobs(settings, {{"render.path", "my-path.json"}}));
  try {
    applyRendererKnobs(settings, {{"render.path", "deferred"}});
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("forward|meshlet|visbuffer or FILE.json"), std::string::npos) << error.what();
  }
}

TEST(RenderSettings, OcclusionIsOffByDefaultAndAFlag) {
  RenderSettings settings;
  EXPECT_FALSE(settings.occlusion);
  EXPECT_FALSE(settings.occlusionHoldBack);
  applyRendererKnobs(settings, {{"render.occlusion", "1"}, {"debug.occlusion_hold_back", "on"}});
  EXPECT_TRUE(settings.occlusion);
  EXPECT_TRUE(settings.occlusionHoldBack);
  applyRendererKnobs(settings, {{"render.occlusion", "off"}});
  EXPECT_FALSE(settings.occlusion);
  EXPECT_THROW(applyRendererKnobs(settings, {{"render.occlusion", "hiz"}}), InputError);
}

TEST(RenderSettings, VisBackingDefaultsToAutoAndRejectsOthers) {
  RenderSettings settings;
  EXPECT_EQ(settings.visBacking, VisBacking::Auto);
  applyRendererKnobs(settings, {{"render.vis_backing", "image"}});
  EXPECT_EQ(settings.visBacking, VisBacking::Image);
  applyRendererKnobs(settings, {{"render.vis_backing", "buffer"}});
  EXPECT_EQ(settings.visBacking, VisBacking::Buffer);
  applyRendererKnobs(settings, {{"render.vis_backing", "auto"}});
  EXPECT_EQ(settings.visBacking, VisBacking::Auto);
  try {
    applyRendererKnobs(settings, {{"render.vis_backing", "texture"}});
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("auto|buffer|image"), std::string::npos) << error.what();
  }
}

// Issue 30: the sweep's reference is made from each knob's role, so every knob fgbench registers
// (the renderer's and the scene's) has one, and approximation knobs name their exact value.
TEST(RenderSettings, EveryKnobHasAReferenceRole) {
  std::vector<KnobSpec> specs = rendererKnobSpecs();
  for (const KnobSpec& spec : scene::knobSpecs()) specs.push_back(spec);
  for (const KnobSpec& spec : specs) {
    EXPECT_NE(spec.role, ReferenceRole::Unset) << spec.key;
    if (spec.role == ReferenceRole::Approximation) {
      EXPECT_TRUE(knobValueValid(spec, spec.exact)) << spec.key;
    }
  }
  KnobRegistry registry;
  EXPECT_NO_THROW(registry.add(specs));
  EXPECT_EQ(registry.find("bloom.mips")->role, ReferenceRole::Look);  // a wider bloom is another look
  EXPECT_EQ(registry.find("render.ssaa")->exact, "4");
  EXPECT_EQ(registry.find("render.path")->exact, "forward");
}

TEST(RenderSettings, KnowsItsKeys) {
  EXPECT_TRUE(isRendererKnob("debug.view"));
  EXPECT_TRUE(isRendererKnob("render.ssaa"));
  EXPECT_TRUE(isRendererKnob("lighting.mode"));
  EXPECT_FALSE(isRendererKnob("post.exposure"));
  for (const KnobSpec& spec : rendererKnobSpecs()) EXPECT_EQ(spec.owner, "renderer") << spec.key;
}

TEST(RenderSettings, SupersamplingScalesTheScenePassesOnly) {
  RenderSettings settings;
  settings.width = 320;
  settings.height = 180;
  applyRendererKnobs(settings, {{"render.ssaa", "3"}});
  EXPECT_EQ(settings.ssaa, 3u);
  EXPECT_EQ(settings.width, 320u);  // the output (bloom, tone mapping, frame.png) keeps its size
  EXPECT_EQ(settings.sceneWidth(), 960u);
  EXPECT_EQ(settings.sceneHeight(), 540u);
  EXPECT_THROW(applyRendererKnobs(settings, {{"render.ssaa", "9"}}), InputError);
  EXPECT_THROW(applyRendererKnobs(settings, {{"render.ssaa", "0"}}), InputError);
}

// Each knob's table line says where its value lands: every field is reached, "none" lands as "".
TEST(RenderSettings, EveryKnobLandsInItsField) {
  RenderSettings settings;
  applyRendererKnobs(settings, {{"bloom.mips", "3"},
                                {"particles.seed", "1073741824"},
                                {"lighting.max_per_cluster", "1024"},
                                {"debug.occlusion_hold_back", "true"},
                                {"debug.record_every_frame", "1"},
                                {"debug.view", "off"},
                                {"debug.inject_nan", "Mesh Render"}});
  EXPECT_EQ(settings.bloomMips, 3u);
  EXPECT_EQ(settings.particleSeedOffset, 1u << 30);
  EXPECT_EQ(settings.maxLightsPerCluster, 1024u);
  EXPECT_TRUE(settings.occlusionHoldBack);
  EXPECT_TRUE(settings.recordEveryFrame);
  EXPECT_EQ(settings.debugView, DebugView::None);
  EXPECT_EQ(settings.injectNanPass, "Mesh Render");
  applyRendererKnobs(settings, {{"debug.inject_nan", "none"}, {"debug.slow_pass", "none"}});
  EXPECT_EQ(settings.injectNanPass, "");
  EXPECT_EQ(settings.slowPass, "");
}

TEST(RenderSettings, LightingMode) {
  RenderSettings settings;
  EXPECT_EQ(settings.lightingMode, LightingMode::Clustered);
  applyRendererKnobs(settings, {{"lighting.mode", "all"}});
  EXPECT_EQ(settings.lightingMode, LightingMode::All);
  applyRendererKnobs(settings, {{"lighting.mode", "clustered"}});
  EXPECT_EQ(settings.lightingMode, LightingMode::Clustered);
  EXPECT_THROW(applyRendererKnobs(settings, {{"lighting.mode", "every"}}), InputError);
}

// debug.slow_pass=PASS:PERCENT: a Text knob, checked against the frame's passes when they are known.
TEST(RenderSettings, SlowPassNamesAPassAndAPercentage) {
  RenderSettings settings;
  applyRendererKnobs(settings, {{"debug.slow_pass", "Cluster Cull (late):200"}});
  EXPECT_EQ(settings.slowPass, "Cluster Cull (late):200");
  const std::vector<std::string> passes{"Cluster Cull", "Cluster Cull (late)", "Bloom", "Bloom"};
  const SlowPass slow = slowPassOf(settings.slowPass, passes);
  EXPECT_EQ(slow.pass, "Cluster Cull (late)");
  EXPECT_DOUBLE_EQ(slow.fraction, 2.0);
  EXPECT_DOUBLE_EQ(slowPassOf("Bloom:12.5", passes).fraction, 0.125);
  for (const char* bad : {"Bloom", "Bloom:", ":50", "Bloom:0", "Bloom:-5", "Bloom:20000", "Bloom:5x", "Bloom:nan"}) {
    try {
      slowPassOf(bad, passes);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      const std::string expected = ": expected PASS:PERCENT with PERCENT a number in (0, 10000], e.g. \"Bloom:50\"";
      EXPECT_EQ(std::string(e.what()), "--set debug.slow_pass=" + std::string(bad) + expected);
    }
  }
  try {
    slowPassOf("Blom:50", passes);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--set debug.slow_pass=Blom:50: no pass 'Blom' in this frame (passes: Cluster Cull, Cluster Cull (late), "
              "Bloom)");
  }
}

}  // namespace
}  // namespace fgb::features
