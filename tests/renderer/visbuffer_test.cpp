// The visibility-buffer path (render.path=visbuffer) through the scene workload: which nodes it
// declares, its image against forward's, occlusion culling, the refused configurations, its
// compute post passes and the opaque-depth test of the colour passes after it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fgb/core/error.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/renderer/scene_workload.hpp>
#include <map>
#include <string>
#include <vector>

#include "scene_render.hpp"

namespace fgb::render {
namespace {

using namespace scene_test;

// render.path=visbuffer: the opaque scene goes through the compute nodes instead of "Mesh Render"
// (transparent meshes and particles stay forward passes), under validation, and the image is the
// forward one up to texture filtering and triangle-edge rounding.
TEST(VisBuffer, ComputeNodesReplaceMeshRenderAndTheImageMatchesForward) {
  const auto vis =
      renderImages(sized(lavapipeConfig("atrium-small.json", {{"render.path", "visbuffer"}}, true), 160, 90, 1), 2);
  const auto forward = renderImages(sized(lavapipeConfig("atrium-small.json", {}), 160, 90, 1), 2);
  EXPECT_EQ(vis.validationMessages, 0u);
  EXPECT_EQ(vis.stats.at("vis_backing_image"), 0.0);  // render.vis_backing=auto: lavapipe has no image atomics
  for (const char* node :
       {"Visibility Clear", "Cluster Cull", "Triangle Filter", "Visibility Raster", "Material Shade"})
    EXPECT_TRUE(vis.passes.count(node)) << node;
  EXPECT_FALSE(vis.passes.count("Mesh Render"));
  EXPECT_TRUE(forward.passes.count("Mesh Render"));
  EXPECT_GT(vis.stats.at("vis_clusters_visible"), 0.0);
  EXPECT_LT(vis.stats.at("vis_clusters_visible"), vis.stats.at("vis_clusters"));  // something was culled
  EXPECT_GT(vis.stats.at("vis_triangles_rasterised"), 0.0);
  EXPECT_EQ(vis.stats.at("vis_large_overflow"), 0.0);
  // Every large triangle has at least one tile job (at most 16 8x8 tiles of its box each).
  EXPECT_GT(vis.stats.at("vis_triangles_large"), 0.0);
  EXPECT_GE(vis.stats.at("vis_raster_tile_jobs"), vis.stats.at("vis_triangles_large"));
  ASSERT_EQ(vis.hdr.pixels.size(), forward.hdr.pixels.size());
  EXPECT_GT(meanOf(vis.hdr), 0.5 * meanOf(forward.hdr));
  EXPECT_LT(differingValues(vis.hdr, forward.hdr, 0.1f, 0.02f), vis.hdr.pixels.size() / 20);
}

// render.occlusion=1 is conservative: the same image as without it, under validation, at
// render.ssaa=1 and 2, over three frames (the first has no HiZ history). A still camera leaves
// phase 2 nothing to recover, so debug.occlusion_hold_back makes phase 1 hold back every other
// cluster: phase 2 must find the visible ones again (appended after phase 1's) and drop the rest.
TEST(VisBuffer, OcclusionCullingKeepsTheImage) {
  for (const char* ssaa : {"1", "2"}) {
    SCOPED_TRACE(std::string("render.ssaa=") + ssaa);
    const auto config = [&](std::map<std::string, std::string> knobs) {
      knobs["render.path"] = "visbuffer";
      knobs["render.ssaa"] = ssaa;
      return sized(lavapipeConfig("atrium-small.json", knobs, true), 160, 90, 1);
    };
    const auto off = renderImages(config({}), 3);
    const auto on = renderImages(config({{"render.occlusion", "1"}}), 3);
    const auto held = renderImages(config({{"render.occlusion", "1"}, {"debug.occlusion_hold_back", "1"}}), 3);
    EXPECT_EQ(on.validationMessages, 0u);
    EXPECT_EQ(held.validationMessages, 0u);
    for (const char* node : {"HiZ Build", "Cluster Cull (late)", "Triangle Filter (late)", "Visibility Raster (late)"}) {
      EXPECT_TRUE(on.passes.count(node)) << node;
      EXPECT_FALSE(off.passes.count(node)) << node;
    }
    EXPECT_FALSE(off.stats.count("vis_occlusion_phase1_occluded"));
    EXPECT_FALSE(on.passes.count("HiZ Build (late)"));  // one pyramid a frame, from phase 1's depths
    // Still camera: phase 1 tests against the very depths phase 2 would, so it recovers nothing.
    EXPECT_EQ(on.stats.at("vis_occlusion_phase2_recovered"), 0.0);
    EXPECT_LE(on.stats.at("vis_clusters_visible"), off.stats.at("vis_clusters_visible"));
    EXPECT_GT(held.stats.at("vis_occlusion_phase2_recovered"), 0.0);
    EXPECT_LE(held.stats.at("vis_occlusion_phase2_recovered"), held.stats.at("vis_occlusion_phase1_occluded"));
    EXPECT_GE(held.stats.at("vis_occlusion_phase1_occluded"), 0.4 * off.stats.at("vis_clusters_visible"));
    ASSERT_EQ(on.hdr.pixels.size(), off.hdr.pixels.size());
    EXPECT_EQ(differingValues(on.hdr, off.hdr, 0.0f, 0.0f), 0u);
    EXPECT_EQ(differingValues(held.hdr, off.hdr, 0.0f, 0.0f), 0u);
  }
  // The forward path has no clusters to cull: the knob is accepted and changes nothing there.
  const auto forward = render(sized(lavapipeConfig("atrium-small.json", {{"render.occlusion", "1"}}), 64, 36, 1), 1);
  const auto names = aliveNames(forward.passes);
  EXPECT_TRUE(names.count("Mesh Render"));
  EXPECT_FALSE(names.count("HiZ Build"));
}

TEST(VisBuffer, RefusesMsaaNamingSupersampling) {
  try {
    (void)openSceneWorkload(sized(lavapipeConfig("atrium-small.json", {{"render.path", "visbuffer"}}), 64, 36, 4));
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("render.ssaa"), std::string::npos) << error.what();
  }
}

// render.vis_backing=image needs 64-bit atomics on R64 storage images: lavapipe has none, so it is
// bad input naming the knob and the device (before any upload); forward ignores the knob.
TEST(VisBuffer, RefusesTheImageBackingWithoutImageAtomics) {
  try {
    (void)openSceneWorkload(
        sized(lavapipeConfig("atrium-small.json", {{"render.path", "visbuffer"}, {"render.vis_backing", "image"}}), 64,
              36, 1));
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("render.vis_backing=image"), std::string::npos) << what;
    EXPECT_NE(what.find("llvmpipe"), std::string::npos) << what;
  }
  EXPECT_NO_THROW((void)openSceneWorkload(sized(
      lavapipeConfig("atrium-small.json", {{"render.path", "forward"}, {"render.vis_backing", "image"}}), 64, 36, 1)));
}

// The 8-bit sRGB code of a display value read back (linear).
int srgbCode(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  const float encoded = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return int(std::lround(encoded * 255.0f));
}

int largestCodeDifference(const ImageRGBA32F& a, const ImageRGBA32F& b) {
  int largest = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    largest = std::max(largest, std::abs(srgbCode(a.pixels[i]) - srgbCode(b.pixels[i])));
  return largest;
}

graph::NodeType nodeType(const Workload& workload, const std::string& name) {
  const graph::FrameGraph& graph = *frameGraphOf(workload);
  return graph.nodes()[nodeIndex(graph, name)].type;
}

// On the visibility-buffer path "SSAA Resolve" and "Tone mapping" are compute nodes running the
// fragment passes' GLSL maths. transparency-only has no opaque mesh, so both paths draw the same
// HDR image: the compute SSAA resolve must give it bit for bit, and the compute tone mapping the
// same display image up to the sRGB encode's rounding: at most one code (lavapipe's sRGB
// attachment encode is approximate, e.g. 28.47 becomes 29; tonemap.comp rounds to nearest). At
// full detail: with render.lod_error > 0 the visibility-buffer path draws transparent meshes' LOD cut.
TEST(VisBuffer, PostPassesAreComputeAndMatchTheFragmentPasses) {
  const std::string scene = kRepositoryScenes + "/transparency-only.json";
  const std::map<std::string, std::string> supersampled = {{"render.ssaa", "2"}, {"render.lod_error", "0"}};
  auto visKnobs = supersampled;
  visKnobs["render.path"] = "visbuffer";
  struct PostPasses {
    Images images;
    graph::NodeType resolve;
    graph::NodeType tonemap;
  };
  // One device at a time: each rendering is read and closed before the next opens.
  const auto renderPost = [](const WorkloadConfig& config) {
    const auto r = render(config, 2);
    return PostPasses{imagesOf(r), nodeType(*r.workload, "SSAA Resolve"), nodeType(*r.workload, "Tone mapping")};
  };
  const auto vis = renderPost(sized(lavapipeConfig(scene, visKnobs, true), 160, 90, 1));
  const auto forward = renderPost(sized(lavapipeConfig(scene, supersampled), 160, 90, 1));
  EXPECT_EQ(vis.resolve, graph::NodeType::Compute);
  EXPECT_EQ(vis.tonemap, graph::NodeType::Compute);
  EXPECT_EQ(forward.resolve, graph::NodeType::Graphics);
  EXPECT_EQ(forward.tonemap, graph::NodeType::Graphics);
  EXPECT_EQ(vis.images.validationMessages, 0u);
  EXPECT_GT(meanOf(vis.images.hdr), 0.0);
  EXPECT_TRUE(vis.images.hdr.pixels == forward.images.hdr.pixels);
  EXPECT_LE(largestCodeDifference(vis.images.display, forward.images.display), 1);
}

// Whether the graph's node `name` declares a depth attachment, and whether it reads the buffer
// "visibility depth" (the opaque depth of the visibility-buffer path).
struct DepthUse {
  bool attachment = false;
  bool readsOpaqueDepthBuffer = false;
};
DepthUse depthUseOf(const Workload& workload, const std::string& name) {
  const graph::FrameGraph& graph = *frameGraphOf(workload);
  const uint32_t index = nodeIndex(graph, name);
  DepthUse use{graph.attachments(index).depth.target.valid(), false};
  for (const auto& access : graph.accesses(index))
    use.readsOpaqueDepthBuffer |=
        graph.resources()[access.resource].name == "visibility depth" && access.access == graph::Access::StorageRead;
  return use;
}

// On the visibility-buffer path no depth image is written ("Visibility Depth Resolve" is gone):
// "Mesh Render Transparent" (render.transparent=raster; compute is the path's default) and
// "Particle Render" have no depth attachment and read the opaque depth buffer, which their
// fragment shaders test against; at render.ssaa=2 too (the buffer is at the scene passes' size),
// under validation, with the culling counters still read back. Forward keeps its depth attachment.
TEST(VisBuffer, LaterColourPassesTestTheOpaqueDepthBufferInsteadOfADepthImage) {
  const std::vector<std::string> laterPasses = {"Mesh Render Transparent", "Particle Render"};
  {  // one device at a time: each rendering is read and closed before the next opens
    const auto vis =
        render(sized(lavapipeConfig("atrium-small.json",
                                    {{"render.path", "visbuffer"}, {"render.ssaa", "2"}, {"render.transparent", "raster"}},
                                    true),
                     160, 90, 1),
               2);
    EXPECT_EQ(vis.workload->validationMessages(), 0u);
    const auto names = aliveNames(vis.passes);
    EXPECT_FALSE(names.count("Visibility Depth Resolve"));
    for (const auto& pass : laterPasses) {
      EXPECT_TRUE(names.count(pass)) << pass;
      const DepthUse use = depthUseOf(*vis.workload, pass);
      EXPECT_FALSE(use.attachment) << pass;
      EXPECT_TRUE(use.readsOpaqueDepthBuffer) << pass;
    }
    EXPECT_GT(vis.workload->stats().at("vis_clusters_visible"), 0.0);  // copied beside "Material Shade"
  }
  const auto forward = render(sized(lavapipeConfig("atrium-small.json", {}), 160, 90, 1), 1);
  for (const auto& pass : laterPasses) {
    const DepthUse use = depthUseOf(*forward.workload, pass);
    EXPECT_TRUE(use.attachment) << pass;
    EXPECT_FALSE(use.readsOpaqueDepthBuffer) << pass;
  }
}

// A user's render path file (bench/paths/visbuffer-fragment-post.json): the visibility buffer with
// the thesis' fragment post passes. The path, not the feature, decides the form: "Tone mapping" and
// "SSAA Resolve" are graphics nodes, the HDR image is render.path=visbuffer's bit for bit (the
// display image may differ by the sRGB encoding: the format's or the compute shader's).
TEST(VisBuffer, AUserPathFileChoosesThePostPassForm) {
  const std::string file = std::string(FGB_BENCH_PATHS_DIR) + "/visbuffer-fragment-post.json";
  for (const char* ssaa : {"1", "2"}) {
    SCOPED_TRACE(std::string("render.ssaa=") + ssaa);
    const auto config = [&](const std::string& path) {
      return sized(lavapipeConfig("atrium-small.json", {{"render.path", path}, {"render.ssaa", ssaa}}, true), 160,
                   90, 1);
    };
    Rendered fragment = render(config(file), 2);
    const graph::FrameGraph* graph = frameGraphOf(*fragment.workload);
    ASSERT_NE(graph, nullptr);
    EXPECT_EQ(graph->nodes()[nodeIndex(*graph, "Tone mapping")].type, graph::NodeType::Graphics);
    if (std::string(ssaa) == "2") {
      EXPECT_EQ(graph->nodes()[nodeIndex(*graph, "SSAA Resolve")].type, graph::NodeType::Graphics);
    }
    EXPECT_EQ(graph->nodes()[nodeIndex(*graph, "Material Shade")].type, graph::NodeType::Compute);
    const Images withFile = imagesOf(fragment);
    fragment = {};
    const Images builtIn = renderImages(config("visbuffer"), 2);
    EXPECT_EQ(withFile.validationMessages, 0u);
    EXPECT_EQ(withFile.hdr.pixels, builtIn.hdr.pixels);
    // One sRGB step, read back as linear values: at most ~0.009 (at 1.0), relatively more near 0.
    EXPECT_EQ(differingValues(withFile.display, builtIn.display, 0.05f, 0.01f), 0u);
  }
}

}  // namespace
}  // namespace fgb::render
