// Graphviz dumps: both detail levels are accepted by `dot -Tsvg`, even with awkward names. The
// test fails (does not skip) when Graphviz is missing: CI must have it.
#include "test_helpers.hpp"

#include <fgb/graph/dot.hpp>

#include <fgb/graph/barrier_names.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fgb::graph::test {
namespace {

namespace fs = std::filesystem;

struct DotFixture : ::testing::Test {
  void SetUp() override {
    ASSERT_STRNE(FGB_DOT_EXECUTABLE, "") << "Graphviz `dot` was not found at configure time";
    ASSERT_TRUE(fs::exists(FGB_DOT_EXECUTABLE)) << FGB_DOT_EXECUTABLE;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() / ("fgb-dot-" + std::to_string(::getpid()) + "-" + info->name());
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  // Writes `text` and renders it; returns dot's exit status (0 = accepted) and checks the SVG.
  int render(const std::string& text, const std::string& stem) {
    const fs::path in = dir / (stem + ".dot");
    const fs::path out = dir / (stem + ".svg");
    std::ofstream(in) << text;
    const std::string command = std::string(FGB_DOT_EXECUTABLE) + " -Tsvg '" + in.string() + "' -o '" +
                                out.string() + "' 2>'" + (dir / (stem + ".err")).string() + "'";
    const int status = std::system(command.c_str());
    if (status == 0) {
      EXPECT_GT(fs::file_size(out), 100u);
    }
    if (status != 0) {
      std::ifstream err(dir / (stem + ".err"));
      std::stringstream buffer;
      buffer << err.rdbuf();
      ADD_FAILURE() << "dot rejected " << stem << ":\n" << buffer.str() << "\n" << text;
    }
    return status;
  }

  fs::path dir;
};

FrameGraph sampleGraph(const std::string& odd) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "swap" + odd);
  const TextureHandle hdr = g.createTexture("hdr" + odd, colorDesc());
  const BufferHandle lights = g.createBuffer("lights {list}", bufferDesc());
  const BufferHandle lights1 = g.addNode("Cull" + odd, NodeType::Compute).write(lights, Access::StorageWrite);
  NodeBuilder forward = g.addNode("Forward" + odd, NodeType::Graphics);
  forward.read(lights1, Access::StorageRead);
  const TextureHandle hdr1 = forward.addColorTarget(hdr);
  NodeBuilder tonemap = g.addNode("Tonemap", NodeType::Graphics);
  tonemap.read(hdr1);
  tonemap.addColorTarget(out);
  g.addNode("Unused debug", NodeType::Compute).read(hdr1);
  return g;
}

TEST_F(DotFixture, BriefAndFullDumpsRender) {
  const FrameGraph g = sampleGraph("");
  const CompiledGraph c = compile(g, queueOptions(2));
  const std::string brief = toDot(g, c, DotDetail::Brief);
  const std::string full = toDot(g, c, DotDetail::Full);
  EXPECT_EQ(render(brief, "brief"), 0);
  EXPECT_EQ(render(full, "full"), 0);
  for (const char* name : {"Cull", "Forward", "Tonemap", "Unused debug", "hdr"}) {
    EXPECT_NE(brief.find(name), std::string::npos) << name;
  }
  EXPECT_GT(full.size(), brief.size());
  // Barriers in words: Cull (compute, queue 1) hands the light list over to Forward on queue 0, and
  // Forward's colour target becomes Tonemap's sampled input.
  EXPECT_NE(full.find("release lights {list}: compute \u2192 none, storage-write \u2192 none, queue 1 \u2192 0"),
            std::string::npos) << full;
  EXPECT_NE(full.find("acquire lights {list}: none \u2192 vertex+fragment, none \u2192 storage-read, queue 1 \u2192 0"),
            std::string::npos) << full;
  EXPECT_NE(full.find("hdr: color-output \u2192 vertex+fragment, color-write \u2192 sampled-read, color-attachment \u2192 shader-read-only"),
            std::string::npos) << full;
  EXPECT_EQ(full.find("0x"), std::string::npos) << "a mask left in hex:\n" << full;
}

TEST(BarrierNames, EveryStageAccessAndLayoutHasAWord) {
  for (uint32_t bit = 1; bit <= kStageAllCommands; bit <<= 1) EXPECT_EQ(stageNames(bit).find("0x"), std::string::npos) << bit;
  for (uint32_t bit = 1; bit <= kAccessHostWrite; bit <<= 1) EXPECT_EQ(accessNames(bit).find("0x"), std::string::npos) << bit;
  EXPECT_EQ(stageNames(kStageEarlyFragmentTests | kStageLateFragmentTests), "early-fragment-tests+late-fragment-tests");
  EXPECT_EQ(accessNames(kAccessNone), "none");
  EXPECT_EQ(accessNames(1u << 30), "0x40000000");  // an unnamed bit stays visible
  for (Layout layout : {Layout::Undefined, Layout::General, Layout::ColorAttachment, Layout::DepthStencilAttachment,
                        Layout::DepthStencilReadOnly, Layout::ShaderReadOnly, Layout::TransferSrc, Layout::TransferDst}) {
    EXPECT_NE(layoutName(layout), "?");
  }
  Barrier release;
  release.kind = Barrier::Kind::Release;
  release.srcStages = kStageComputeShader;
  release.srcAccess = kAccessShaderStorageWrite;
  release.srcQueue = 1;
  release.dstQueue = 0;
  EXPECT_EQ(describeBarrier(release, "lights", false), "release lights: compute \u2192 none, storage-write \u2192 none, queue 1 \u2192 0");
}

TEST_F(DotFixture, NamesWithQuotesBracesAndAnglesAreEscaped) {
  const FrameGraph g = sampleGraph(" \"q\" <a|b> {c} \\ ;");
  const CompiledGraph c = compile(g, queueOptions(3));
  EXPECT_EQ(render(toDot(g, c, DotDetail::Brief), "brief"), 0);
  EXPECT_EQ(render(toDot(g, c, DotDetail::Full), "full"), 0);
}

TEST_F(DotFixture, EmptyAndFullyCulledGraphsRender) {
  FrameGraph empty;
  EXPECT_EQ(render(toDot(empty, compile(empty), DotDetail::Full), "empty"), 0);
  FrameGraph culled;
  culled.addNode("Nothing", NodeType::Compute).write(culled.createBuffer("b", bufferDesc()), Access::StorageWrite);
  const CompiledGraph c = compile(culled);
  const std::string text = toDot(culled, c, DotDetail::Full);
  EXPECT_NE(text.find("Nothing"), std::string::npos);
  EXPECT_EQ(render(text, "culled"), 0);
}

}  // namespace
}  // namespace fgb::graph::test
