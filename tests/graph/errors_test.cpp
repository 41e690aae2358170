// Bad input: each is a GraphError whose message names the nodes and resources involved, never a
// crash. (Cycles are covered in edges_cycles_test.cpp.)
#include "test_helpers.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

namespace fgb::graph::test {
namespace {

using ::testing::HasSubstr;

// Runs `action`, expecting a GraphError; returns its message ("" if none was thrown).
std::string graphErrorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const GraphError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected a GraphError";
  return "";
}

TEST(BadInput, ReadingAVersionNobodyWroteNamesNodeAndResource) {
  FrameGraph graph;
  const TextureHandle fresh = graph.createTexture("gbuffer", colorDesc());
  NodeBuilder node = graph.addNode("Lighting", NodeType::Compute);
  const std::string message = graphErrorOf([&] { node.read(fresh, Access::Sampled); });
  EXPECT_THAT(message, HasSubstr("Lighting"));
  EXPECT_THAT(message, HasSubstr("gbuffer"));
}

TEST(BadInput, ReadWriteOfANeverWrittenTransientIsAReadOfNothing) {
  FrameGraph graph;
  const BufferHandle fresh = graph.createBuffer("counters", bufferDesc());
  NodeBuilder node = graph.addNode("Accumulate", NodeType::Compute);
  const std::string message = graphErrorOf([&] { node.write(fresh, Access::StorageReadWrite); });
  EXPECT_THAT(message, HasSubstr("Accumulate"));
  EXPECT_THAT(message, HasSubstr("counters"));
}

TEST(BadInput, WritingAStaleVersionNamesNodeResourceAndSaysStale) {
  FrameGraph graph;
  const TextureHandle v0 = graph.createTexture("hdr", colorDesc());
  graph.addNode("First", NodeType::Compute).write(v0, Access::StorageWrite);
  NodeBuilder second = graph.addNode("Second", NodeType::Compute);
  const std::string message = graphErrorOf([&] { second.write(v0, Access::StorageWrite); });
  EXPECT_THAT(message, HasSubstr("stale"));
  EXPECT_THAT(message, HasSubstr("Second"));
  EXPECT_THAT(message, HasSubstr("hdr"));
}

TEST(BadInput, DependentExtentOnAnUnknownResourceNamesTheTexture) {
  FrameGraph graph;
  TextureDesc desc = colorDesc();
  desc.extentFrom = TextureHandle{4242};
  const std::string message = graphErrorOf([&] {
    graph.createTexture("bloom-half", desc);
    (void)compile(graph);
  });
  EXPECT_THAT(message, HasSubstr("bloom-half"));
}

TEST(BadInput, DependentSizeOnAnUnknownResourceNamesTheBuffer) {
  FrameGraph graph;
  BufferDesc desc;
  desc.sizeFrom = BufferHandle{77};
  const std::string message = graphErrorOf([&] {
    graph.createBuffer("visible-list", desc);
    (void)compile(graph);
  });
  EXPECT_THAT(message, HasSubstr("visible-list"));
}

TEST(BadInput, DependentExtentNamingABufferIsRejected) {
  FrameGraph graph;
  const BufferHandle buffer = graph.createBuffer("args", bufferDesc());
  TextureDesc desc = colorDesc();
  desc.extentFrom = TextureHandle{buffer.version};
  const std::string message = graphErrorOf([&] { graph.createTexture("half", desc); });
  EXPECT_THAT(message, HasSubstr("half"));
  EXPECT_THAT(message, HasSubstr("args"));
}

TEST(BadInput, InvalidAndUnknownHandlesAreErrors) {
  FrameGraph graph;
  NodeBuilder node = graph.addNode("Pass", NodeType::Compute);
  EXPECT_THAT(graphErrorOf([&] { node.read(TextureHandle{}, Access::Sampled); }), HasSubstr("Pass"));
  EXPECT_THAT(graphErrorOf([&] { node.write(BufferHandle{999}, Access::StorageWrite); }), HasSubstr("Pass"));
}

TEST(BadInput, UsingATextureVersionAsABufferIsAnError) {
  FrameGraph graph;
  const TextureHandle texture = importOutput(graph, "swapchain");
  NodeBuilder node = graph.addNode("Copy", NodeType::Transfer);
  const std::string message = graphErrorOf([&] { node.read(BufferHandle{texture.version}, Access::TransferSrc); });
  EXPECT_THAT(message, HasSubstr("swapchain"));
}

TEST(BadInput, AccessKindMustMatchReadOrWrite) {
  FrameGraph graph;
  const TextureHandle texture = importOutput(graph, "out");
  NodeBuilder node = graph.addNode("Mixed", NodeType::Compute);
  EXPECT_THAT(graphErrorOf([&] { node.read(texture, Access::StorageWrite); }), HasSubstr("Mixed"));
  EXPECT_THAT(graphErrorOf([&] { node.write(texture, Access::Sampled); }), HasSubstr("Mixed"));
}

TEST(BadInput, AnUnknownAccessIsAnErrorNamingTheNode) {
  FrameGraph graph;
  const TextureHandle texture = importOutput(graph, "out");
  NodeBuilder node = graph.addNode("Odd", NodeType::Compute);
  const auto unknown = static_cast<Access>(200);
  EXPECT_THAT(graphErrorOf([&] { node.read(texture, unknown); }), HasSubstr("unknown access 200"));
  EXPECT_THAT(graphErrorOf([&] { node.write(texture, unknown); }), HasSubstr("Odd"));
  EXPECT_TRUE(usesOf(graph, 0).empty());
}

TEST(BadInput, AnUnknownNodeTypeOrQueueClassIsAnErrorNamingTheNode) {
  FrameGraph graph;
  EXPECT_THAT(graphErrorOf([&] { graph.addNode("Strange", static_cast<NodeType>(7)); }),
              HasSubstr("'Strange': unknown node type 7"));
  EXPECT_THAT(graphErrorOf([&] { graph.addNode("Lost", NodeType::Compute, static_cast<QueueClass>(9)); }),
              HasSubstr("queue class 9"));
  EXPECT_TRUE(graph.nodes().empty());
}

TEST(BadInput, AttachmentsNeedAGraphicsNode) {
  FrameGraph graph;
  const TextureHandle texture = importOutput(graph, "out");
  NodeBuilder node = graph.addNode("NotRaster", NodeType::Compute);
  EXPECT_THAT(graphErrorOf([&] { node.addColorTarget(texture); }), HasSubstr("NotRaster"));
}

TEST(BadInput, ASecondDepthTargetIsAnError) {
  FrameGraph graph;
  const TextureHandle depth = graph.createTexture("depth", colorDesc(256, 256, Format::D32Sfloat));
  NodeBuilder node = graph.addNode("Shadows", NodeType::Graphics);
  const TextureHandle written = node.setDepthStencil(depth);
  const std::string message = graphErrorOf([&] { node.setDepthStencilReadOnly(written); });
  EXPECT_THAT(message, HasSubstr("Shadows"));
  EXPECT_THAT(message, HasSubstr("two depth targets"));
}

TEST(BadInput, ABuilderUsedAfterTheNextNodeWasAddedIsAnError) {
  FrameGraph graph;
  const TextureHandle out = importOutput(graph, "out");
  NodeBuilder first = graph.addNode("First", NodeType::Graphics);
  graph.addNode("Second", NodeType::Graphics);
  const std::string message = graphErrorOf([&] { first.addColorTarget(out); });
  EXPECT_THAT(message, HasSubstr("First"));
  EXPECT_THAT(message, HasSubstr("after the next node was added"));
  EXPECT_TRUE(graph.attachments(0).color.empty());
}

TEST(BadInput, AQueueClassMappedPastTheQueueCountIsAnError) {
  FrameGraph graph;
  const TextureHandle out = importOutput(graph, "out");
  graph.addNode("Fill", NodeType::Compute).write(out, Access::StorageWrite);
  CompileOptions options;
  options.queueCount = 2;
  options.queueOfClass = {0, 2, 0};  // compute -> queue 2, but only queues 0 and 1 exist
  EXPECT_FALSE(graphErrorOf([&] { (void)compile(graph, options); }).empty());
}

TEST(BadInput, ErrorsLeaveTheGraphUsable) {
  FrameGraph graph;
  const TextureHandle v0 = graph.createTexture("t", colorDesc());
  NodeBuilder writer = graph.addNode("W", NodeType::Compute);
  const TextureHandle v1 = writer.write(v0, Access::StorageWrite);
  EXPECT_THROW(writer.write(v0, Access::StorageWrite), GraphError);
  const TextureHandle out = importOutput(graph, "out");
  NodeBuilder reader = graph.addNode("R", NodeType::Compute);
  reader.read(v1, Access::Sampled);
  reader.write(out, Access::StorageWrite);
  const CompiledGraph compiled = compile(graph);
  EXPECT_EQ(compiled.order.size(), 2u);
}

}  // namespace
}  // namespace fgb::graph::test
