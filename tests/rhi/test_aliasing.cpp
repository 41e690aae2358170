// Two transient textures whose lifetimes do not overlap share memory; both still read back right.
#include "gpu_support.hpp"

namespace fgb::test {
namespace {

constexpr uint32_t kSize = 32;
constexpr uint64_t kImageBytes = kSize * kSize * 4;

class Aliasing : public GpuTest {};

TEST_F(Aliasing, AliasedTexturesKeepTheirOwnContents) {
  const auto readback = readbackBuffer("aliasing readback", 2 * kImageBytes);
  graph::FrameGraph g;
  const graph::TextureDesc desc{graph::Format::R8G8B8A8Unorm, {kSize, kSize, 1}};
  graph::TextureHandle first = g.createTexture("first", desc);
  graph::TextureHandle second = g.createTexture("second", desc);
  graph::BufferHandle token = g.createBuffer("order token", {256});
  graph::BufferHandle out = g.importBuffer("readback", {2 * kImageBytes}, rhi::external(readback), kHostRead, kHostRead);

  {  // the clear colour is the content: no job needed
    auto node = g.addNode("Clear first red", graph::NodeType::Graphics);
    first = node.addColorTarget(first, graph::LoadOp::Clear, graph::ClearValue{{1, 0, 0, 1}});
  }
  {
    auto node = g.addNode("Copy first", graph::NodeType::Transfer);
    node.read(first, graph::Access::TransferSrc);
    out = node.write(out, graph::Access::TransferDst);
    token = node.write(token, graph::Access::TransferDst);
    node.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyTextureToBuffer(ctx.texture(first), ctx.buffer(out), 0);
      ctx.cmd().fillBuffer(ctx.buffer(token), 0, 256, 1);
    });
  }
  {  // reads the token: runs after "Copy first", so "second" can take "first"'s memory
    auto node = g.addNode("Clear second green", graph::NodeType::Graphics);
    node.read(token, graph::Access::Uniform);
    second = node.addColorTarget(second, graph::LoadOp::Clear, graph::ClearValue{{0, 1, 0, 1}});
  }
  {
    auto node = g.addNode("Copy second", graph::NodeType::Transfer);
    node.sideEffect();
    node.read(second, graph::Access::TransferSrc);
    out = node.write(out, graph::Access::TransferDst);
    node.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyTextureToBuffer(ctx.texture(second), ctx.buffer(out), kImageBytes);
    });
  }
  const uint32_t firstResource = g.resourceOf(first);
  const uint32_t secondResource = g.resourceOf(second);
  auto graph = device_->compile(std::move(g), {.name = "aliasing"});
  const auto& placements = graph->compiled().aliasing.placements;
  ASSERT_NE(placements[firstResource].heap, graph::kInvalidIndex);
  ASSERT_EQ(placements[firstResource].heap, placements[secondResource].heap) << "the two textures were not aliased";
  EXPECT_EQ(placements[firstResource].offset, placements[secondResource].offset);

  for (int frame = 0; frame < 3; ++frame) device_->execute(*graph);
  device_->waitIdle();
  const auto bytes = device_->mapped(readback);
  for (size_t p = 0; p < kSize * kSize; ++p) {
    const size_t a = p * 4;
    const size_t b = kImageBytes + p * 4;
    ASSERT_EQ(std::to_integer<int>(bytes[a + 0]), 255) << "first, pixel " << p;
    ASSERT_EQ(std::to_integer<int>(bytes[a + 1]), 0) << "first, pixel " << p;
    ASSERT_EQ(std::to_integer<int>(bytes[b + 0]), 0) << "second, pixel " << p;
    ASSERT_EQ(std::to_integer<int>(bytes[b + 1]), 255) << "second, pixel " << p;
  }
}

}  // namespace
}  // namespace fgb::test
