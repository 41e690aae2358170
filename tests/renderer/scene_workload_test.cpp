// Renders small scenes through the scene workload and checks what the frame graph declares (the
// thesis' node names, and no work a scene does not need) and that the image is plausible.
#include <fgb/core/error.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/renderer/scene_workload.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <vector>
#include <string>

#include "scene_render.hpp"

namespace fgb::render {
using namespace scene_test;
namespace {

// The thesis' pass names, in the order the renderer declares them.
std::vector<std::string> thesisPasses(const std::vector<PassTiming>& passes) {
  static const std::set<std::string> kThesis = {
      "Clustered Light Cull", "Particle Emit", "Particle Update", "Particle Render",
      "Mesh Frustum Cull",    "Mesh Render",   "Bloom",           "Tone mapping"};
  std::vector<std::string> names;
  for (const auto& pass : passes)
    if (!pass.culled && kThesis.count(pass.name)) names.push_back(pass.name);
  return names;
}

Rendered renderRepositoryScene(const std::string& scene, bool validation = false) {
  WorkloadConfig config;
  config.scenePath = kRepositoryScenes + "/" + scene;
  config.device = "lavapipe";
  config.validation = validation;
  config.width = 160;
  config.height = 90;
  Rendered result{openSceneWorkload(config), {}};
  result.workload->renderFrame();
  const auto rest = result.workload->finish();
  if (!rest.empty()) result.passes = rest.back().passes;
  return result;
}

TEST(SceneWorkload, EmptySceneDeclaresOnlyClearAndToneMapping) {
  auto r = renderRepositoryScene("empty.json");
  EXPECT_EQ(aliveNames(r.passes), (std::set<std::string>{"Clear", "Tone mapping"}));
}

TEST(SceneWorkload, EmptySceneRunsCleanUnderValidation) {
  auto r = renderRepositoryScene("empty.json", true);
  EXPECT_EQ(r.workload->validationMessages(), 0u);
}

TEST(SceneWorkload, NoLightsSceneDeclaresNoLightOrParticleWork) {
  auto r = renderRepositoryScene("no-lights.json");
  EXPECT_EQ(thesisPasses(r.passes),
            (std::vector<std::string>{"Mesh Frustum Cull", "Mesh Render", "Bloom", "Tone mapping"}));
  for (const auto& name : aliveNames(r.passes)) {
    EXPECT_FALSE(name.starts_with("Particle")) << name;
    EXPECT_FALSE(name.starts_with("Cluster")) << name;
  }
  const auto stats = r.workload->stats();
  EXPECT_EQ(stats.at("lights"), 0.0);
  EXPECT_GT(stats.at("instances_visible"), 0.0);
  EXPECT_LE(stats.at("instances_visible"), stats.at("instances"));
}

TEST(SceneWorkload, AtriumDeclaresEveryThesisPassInOrder) {
  auto r = renderRepositoryScene("atrium.json");
  EXPECT_EQ(thesisPasses(r.passes),
            (std::vector<std::string>{"Clustered Light Cull", "Mesh Frustum Cull", "Mesh Render", "Particle Emit",
                                      "Particle Update", "Particle Render", "Bloom", "Tone mapping"}));
  const auto stats = r.workload->stats();
  EXPECT_EQ(stats.at("instances"), 115.0);
  EXPECT_EQ(stats.at("lights"), 28.0);
}

TEST(SceneWorkload, ShowcaseLightsTheObjects) {
  auto r = render("showcase-small.json");
  EXPECT_GT(meanOf(r.workload->readDisplay()), 0.02);
}

TEST(SceneWorkload, AtriumUsesTheThesisPasses) {
  auto r = render("atrium-small.json", {}, 2);
  const auto names = aliveNames(r.passes);
  for (const char* expected : {"Clustered Light Cull", "Mesh Frustum Cull", "Mesh Render", "Tone mapping"})
    EXPECT_TRUE(names.count(expected)) << expected;
  // The cull shader writes the host's copy of the counts itself: no copy node in the frame.
  EXPECT_EQ(names.count("Light Stats Readback"), 0u);
  const auto stats = r.workload->stats();
  EXPECT_EQ(stats.at("lights"), 28.0);
  EXPECT_GT(stats.at("lights_per_cluster_max"), 0.0);
  EXPECT_GE(stats.at("lights_per_cluster_max"), stats.at("lights_per_cluster_avg"));
  EXPECT_GT(stats.at("instances_visible"), 0.0);
  EXPECT_LE(stats.at("instances_visible"), stats.at("instances"));
  EXPECT_LE(stats.at("triangles_visible"), stats.at("triangles"));
  // The packed multi-draws hold only groups with a visible instance (lavapipe has draw counts).
  EXPECT_GT(stats.at("draws_issued"), 0.0);
  EXPECT_LE(stats.at("draws_issued"), stats.at("instances_visible"));
}

TEST(SceneWorkload, LightComplexityViewChangesTheImage) {
  auto normal = render("showcase-small.json", {}, 1);
  auto heat = render("showcase-small.json", {{"debug.view", "light-complexity"}}, 1);
  const auto a = normal.workload->readDisplay();
  const auto b = heat.workload->readDisplay();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) differing += std::abs(a.pixels[i] - b.pixels[i]) > 0.05f;
  EXPECT_GT(differing, a.pixels.size() / 20);
  // Same passes: the debug view is a shader branch, not extra work.
  EXPECT_EQ(aliveNames(normal.passes), aliveNames(heat.passes));
}

TEST(SceneWorkload, HdrImageIsFiniteAndNonNegative) {
  auto r = render("showcase-small.json", {}, 1);
  const auto hdr = r.workload->readHdr();
  ASSERT_EQ(hdr.pixels.size(), size_t{320} * 180 * 4);
  EXPECT_TRUE(std::all_of(hdr.pixels.begin(), hdr.pixels.end(), [](float v) { return std::isfinite(v) && v >= 0.0f; }));
  EXPECT_GT(meanOf(hdr), 0.0);
}

}  // namespace
}  // namespace fgb::render

namespace fgb::render {
namespace {

TEST(SceneWorkload, DepthPrepassAddsItsNodeAndKeepsTheImage) {
  auto plain = render("showcase-small.json", {}, 1);
  auto prepass = render("showcase-small.json", {{"render.depth_prepass", "1"}}, 1);
  EXPECT_FALSE(aliveNames(plain.passes).count("Depth Prepass"));
  EXPECT_TRUE(aliveNames(prepass.passes).count("Depth Prepass"));
  const auto a = plain.workload->readHdr();
  const auto b = prepass.workload->readHdr();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) differing += std::abs(a.pixels[i] - b.pixels[i]) > 1e-3f;
  EXPECT_LT(differing, a.pixels.size() / 1000);  // invariant positions: same depth, same surfaces
}

TEST(SceneWorkload, ParticlesAreDeterministicBySeedAndFrame) {
  auto a = render(kRepositoryScenes + "/particles-only.json", {}, 20);
  auto b = render(kRepositoryScenes + "/particles-only.json", {}, 20);
  auto c = render(kRepositoryScenes + "/particles-only.json", {{"particles.seed", "7"}}, 20);
  const auto imageA = a.workload->readHdr();
  EXPECT_EQ(imageA.pixels, b.workload->readHdr().pixels);
  EXPECT_NE(imageA.pixels, c.workload->readHdr().pixels);
  EXPECT_GT(meanOf(imageA), meanOf(render(kRepositoryScenes + "/empty.json", {}, 1).workload->readHdr()));
}

}  // namespace
}  // namespace fgb::render

// Supersampling (render.ssaa), lighting.mode and the reference configuration.
namespace fgb::render {
namespace {

// The box filter the SSAA resolve documents: output pixel = mean of its factor x factor block.
ImageRGBA32F boxDownsample(const ImageRGBA32F& image, uint32_t factor) {
  ImageRGBA32F out{image.width / factor, image.height / factor, {}};
  out.pixels.assign(size_t{out.width} * out.height * 4, 0.0f);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x)
      for (uint32_t c = 0; c < 4; ++c) {
        float sum = 0.0f;
        for (uint32_t dy = 0; dy < factor; ++dy)
          for (uint32_t dx = 0; dx < factor; ++dx)
            sum += image.pixels[((size_t{y} * factor + dy) * image.width + x * factor + dx) * 4 + c];
        out.pixels[(size_t{y} * out.width + x) * 4 + c] = sum / float(factor * factor);
      }
  return out;
}

// render.ssaa=2 at 160x90 must equal the scene rendered at 320x180, box-filtered 2x2: the scene
// passes (meshes, particles) ran at twice the size, and the resolve is the documented filter.
// Every light is shaded (lighting.mode=all) so the cluster tiling, which follows the output size,
// cannot differ. Validation is on: the resolve node's accesses are checked too.
TEST(Supersampling, ResolvesTheScenePassesRenderedAtTwiceTheSizeWithABoxFilter) {
  const auto supersampled = renderImages(
      sized(lavapipeConfig("atrium-small.json", {{"render.ssaa", "2"}, {"lighting.mode", "all"}}, true), 160, 90, 1),
      1);
  const auto large =
      renderImages(sized(lavapipeConfig("atrium-small.json", {{"lighting.mode", "all"}}), 320, 180, 1), 1);
  const auto plain =
      renderImages(sized(lavapipeConfig("atrium-small.json", {{"lighting.mode", "all"}}), 160, 90, 1), 1);
  EXPECT_EQ(supersampled.validationMessages, 0u);
  EXPECT_TRUE(supersampled.passes.count("SSAA Resolve"));
  EXPECT_FALSE(large.passes.count("SSAA Resolve"));

  const auto& hdr = supersampled.hdr;
  ASSERT_EQ(hdr.width, 160u);
  ASSERT_EQ(hdr.height, 90u);
  EXPECT_EQ(supersampled.display.width, 160u);  // bloom and tone mapping ran at the output size
  const auto expected = boxDownsample(large.hdr, 2);
  ASSERT_EQ(expected.pixels.size(), hdr.pixels.size());
  EXPECT_GT(meanOf(hdr), 0.0);
  // R16F keeps 11 significant bits: the resolve rounds its mean once (relative error <= 2^-11).
  EXPECT_EQ(differingValues(hdr, expected, 1.0e-3f, 1.0e-5f), 0u);
  // ... and is not trivially the 1x image: edges are smoother, so some pixels differ.
  EXPECT_GT(differingValues(hdr, plain.hdr, 1.0e-2f, 1.0e-3f), hdr.pixels.size() / 100);
}

TEST(LightingMode, AllShadesEveryLightWithoutClusterPasses) {
  const auto all = renderImages(lavapipeConfig("atrium-small.json", {{"lighting.mode", "all"}}), 1);
  for (const auto& name : all.passes) EXPECT_FALSE(name.starts_with("Cluster")) << name;
  EXPECT_TRUE(all.passes.count("Mesh Render"));

  // Clustered lists that never overflow keep every light that reaches a fragment: same image up to
  // the order of the sum (and the rare fragment on a cluster's edge).
  const auto uncapped = renderImages(lavapipeConfig("atrium-small.json", {{"lighting.max_per_cluster", "1024"}}), 1);
  EXPECT_LT(differingValues(all.hdr, uncapped.hdr, 1.0e-2f, 1.0e-3f), all.hdr.pixels.size() / 1000);
  // With one light per cluster the clustered image loses light where lights overlap; `all` has no cap.
  const auto capped = renderImages(lavapipeConfig("atrium-small.json", {{"lighting.max_per_cluster", "1"}}), 1);
  ASSERT_GT(capped.stats.at("lights_per_cluster_max"), 1.0);
  EXPECT_GT(differingValues(all.hdr, capped.hdr, 1.0e-2f, 1.0e-3f), all.hdr.pixels.size() / 100);
}

// The reference configuration (render.ssaa=4, lavapipe's largest MSAA 4, every light for every
// pixel, the full bloom chain) renders bit-identically twice, under validation.
TEST(Reference, TwoRendersAreBitIdentical) {
  const std::map<std::string, std::string> reference = {
      {"render.ssaa", "4"}, {"lighting.mode", "all"}, {"bloom.mips", "10"}};
  const auto config = sized(lavapipeConfig("atrium-small.json", reference, true), 160, 90, 4);
  const auto first = renderImages(config, 2);
  const auto second = renderImages(config, 2);
  EXPECT_EQ(first.validationMessages, 0u);
  EXPECT_EQ(second.validationMessages, 0u);
  EXPECT_TRUE(first.passes.count("SSAA Resolve"));
  EXPECT_GT(meanOf(first.hdr), 0.0);
  EXPECT_TRUE(first.hdr.pixels == second.hdr.pixels);
  EXPECT_TRUE(first.display.pixels == second.display.pixels);
}

}  // namespace
}  // namespace fgb::render

// --check-finite: reduction nodes after every pass writing float colour data; the first bad pass.
namespace fgb::render {
namespace {

std::string firstBadPass(const std::vector<NonFiniteCounts>& counts) {
  for (const auto& c : counts)
    if (c.bad()) return c.pass;
  return "";
}

Rendered renderChecked(std::map<std::string, std::string> knobs, uint32_t msaa) {
  auto config = sized(lavapipeConfig("atrium-small.json", std::move(knobs), true), 160, 90, msaa);
  config.checkFinite = true;
  return render(config, 1);
}

TEST(CheckFinite, OffDeclaresNothing) {
  const auto plain = render(sized(lavapipeConfig("atrium-small.json", {}), 160, 90, 1), 1);
  for (const auto& pass : plain.passes) EXPECT_FALSE(pass.name.starts_with("Finite Check")) << pass.name;
  EXPECT_TRUE(plain.workload->nonFiniteCounts().empty());
}

TEST(CheckFinite, CleanFrameHasNoBadPass) {
  const auto checked = renderChecked({}, 1);
  EXPECT_EQ(checked.workload->validationMessages(), 0u);
  const auto counts = checked.workload->nonFiniteCounts();
  std::vector<std::string> names;
  for (const auto& c : counts) names.push_back(c.pass);
  // Execution order; every pass writing the HDR image or a bloom level is checked.
  EXPECT_EQ(names, (std::vector<std::string>{"Mesh Render", "Mesh Render Transparent", "Particle Render", "Bloom"}));
  EXPECT_EQ(firstBadPass(counts), "");
  EXPECT_TRUE(aliveNames(checked.passes).count("Finite Check: Bloom"));
}

// A NaN written by one pass spreads to the passes after it; the report must name the one that wrote
// it first. MSAA 4 with SSAA 2: the multisampled target, the resolve and the SSAA resolve are checked.
TEST(CheckFinite, NamesThePassThatInjectedTheNan) {
  const auto mesh = renderChecked({{"debug.inject_nan", "Mesh Render"}, {"render.ssaa", "2"}}, 4);
  EXPECT_EQ(mesh.workload->validationMessages(), 0u);
  const auto meshCounts = mesh.workload->nonFiniteCounts();
  EXPECT_EQ(firstBadPass(meshCounts), "Mesh Render");
  for (const auto& c : meshCounts) {
    if (c.pass == "SSAA Resolve") {
      EXPECT_GT(c.nan, 0u);  // it spread through the resolve
    }
  }

  const auto bloom = renderChecked({{"debug.inject_nan", "Bloom"}}, 1);
  const auto bloomCounts = bloom.workload->nonFiniteCounts();
  EXPECT_EQ(firstBadPass(bloomCounts), "Bloom");
  ASSERT_FALSE(bloomCounts.empty());
  EXPECT_EQ(bloomCounts.back().pass, "Bloom");
  EXPECT_EQ(bloomCounts.back().nan, 1u);
}

}  // namespace
}  // namespace fgb::render

namespace fgb::render {
namespace {

// The light cull's lists hold every light that reaches a cluster, over several 64-light chunks
// (150 lights): with no overflow the clustered image is the every-light reference's.
TEST(LightingMode, ClusteredListsKeepEveryLightAcrossChunks) {
  const auto all = renderImages(lavapipeConfig("many-lights-small.json", {{"lighting.mode", "all"}}), 1);
  const auto clustered =
      renderImages(lavapipeConfig("many-lights-small.json", {{"lighting.max_per_cluster", "1024"}}, true), 1);
  EXPECT_EQ(clustered.validationMessages, 0u);
  ASSERT_EQ(clustered.stats.at("lights"), 150.0);
  EXPECT_GT(clustered.stats.at("lights_per_cluster_max"), 64.0);  // a cluster's list spans chunks
  EXPECT_EQ(clustered.stats.at("clusters_overflowed"), 0.0);
  EXPECT_GT(meanOf(clustered.hdr), 0.0);
  EXPECT_LT(differingValues(all.hdr, clustered.hdr, 1.0e-2f, 1.0e-3f), all.hdr.pixels.size() / 1000);
}

// With MSAA the resolve is its own node, declared after the last colour pass; single-sampled
// there is none (the colour passes wrote the HDR image).
TEST(MsaaResolve, IsItsOwnNodeAfterTheLastColourPass) {
  {
    const auto msaa = render(sized(lavapipeConfig("atrium-small.json", {}, true), 160, 90, 4), 1);
    EXPECT_EQ(msaa.workload->validationMessages(), 0u);
    const auto& nodes = frameGraphOf(*msaa.workload)->nodes();
    const auto position = [&](const std::string& name) {
      return std::find_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n.name == name; }) - nodes.begin();
    };
    ASSERT_LT(position("MSAA Resolve"), std::ptrdiff_t(nodes.size()));
    EXPECT_GT(position("MSAA Resolve"), position("Particle Render"));
    EXPECT_GT(position("MSAA Resolve"), position("Mesh Render Transparent"));
    EXPECT_LT(position("MSAA Resolve"), position("Bloom"));
    EXPECT_TRUE(aliveNames(msaa.passes).count("MSAA Resolve"));
  }
  const auto single = render(sized(lavapipeConfig("atrium-small.json", {}), 160, 90, 1), 1);
  EXPECT_FALSE(aliveNames(single.passes).count("MSAA Resolve"));
}

}  // namespace
}  // namespace fgb::render

// render.async measured: compiling the frame graph for one queue and back between frames keeps
// the features' state (particles, the occlusion pyramid, exposure), so the frames after it are
// the frames a run without the switch renders, and validation stays silent across the switch.
namespace fgb::render {
namespace {

TEST(AsyncCompute, RecompilingForOneQueueAndBackKeepsTheFrames) {
  const std::map<std::string, std::string> knobs = {{"render.path", "visbuffer"}, {"render.occlusion", "1"}};
  const auto config = sized(lavapipeConfig("atrium-small.json", knobs, true), 160, 90, 1);
  const auto straight = renderImages(config, 4);

  Rendered switched{openSceneWorkload(config), {}};
  Workload& workload = *switched.workload;
  EXPECT_EQ(workload.queuesUsed(), 1u);  // lavapipe has one queue
  workload.renderFrame();
  workload.finish();
  ASSERT_TRUE(workload.setAsyncCompute(false));
  workload.renderFrame();
  workload.renderFrame();
  workload.finish();
  ASSERT_TRUE(workload.setAsyncCompute(true));
  workload.renderFrame();
  const auto last = workload.finish();
  ASSERT_FALSE(last.empty());
  switched.passes = last.back().passes;
  const auto images = imagesOf(switched);
  EXPECT_EQ(images.validationMessages, 0u);
  EXPECT_EQ(images.passes, straight.passes);
  EXPECT_TRUE(images.hdr.pixels == straight.hdr.pixels);
}

}  // namespace
}  // namespace fgb::render
