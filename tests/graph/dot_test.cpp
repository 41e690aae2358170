// Graphviz dumps: both detail levels are accepted by `dot -Tsvg`, even with awkward names. The
// test fails (does not skip) when Graphviz is missing: CI must have it.
#include "test_helpers.hpp"

#include <fgb/graph/dot.hpp>

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
  EXPECT_NE(full.find("SHADER_READ_ONLY"), std::string::npos);  // barriers/layouts in the full dump
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
