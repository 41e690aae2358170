// Lifetimes (positions in the global order), dependent fields, and transient memory aliasing.
#include "test_helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace fgb::graph::test {
namespace {

constexpr uint64_t kSize = 1 << 20;

// A -> B -> C -> D, each handing the next a fresh 1 MiB transient; D writes the output.
struct Chain {
  FrameGraph graph;
  std::vector<uint32_t> transients;
};

Chain chainOfFour() {
  Chain c;
  FrameGraph& g = c.graph;
  const BufferHandle out = g.importBuffer("out", bufferDesc(), {1}, {}, {});
  BufferHandle previous{};
  const char* names[] = {"A", "B", "C"};
  for (const char* name : names) {
    const BufferHandle t = g.createBuffer(std::string("t") + name, bufferDesc(kSize));
    c.transients.push_back(g.resourceOf(t));
    NodeBuilder b = g.addNode(name, NodeType::Compute);
    if (previous.valid()) b.read(previous, Access::StorageRead);
    previous = b.write(t, Access::StorageWrite);
  }
  NodeBuilder d = g.addNode("D", NodeType::Compute);
  d.read(previous, Access::StorageRead);
  d.write(out, Access::StorageWrite);
  return c;
}

TEST(Lifetimes, SpanFirstToLastUseInOrder) {
  const Chain c = chainOfFour();
  const CompiledGraph compiled = compile(c.graph);
  const Lifetime& tA = compiled.lifetimes[c.transients[0]];
  EXPECT_EQ(tA.first, compiled.nodes[nodeNamed(c.graph, "A")].orderIndex);
  EXPECT_EQ(tA.last, compiled.nodes[nodeNamed(c.graph, "B")].orderIndex);
  const Lifetime& tC = compiled.lifetimes[c.transients[2]];
  EXPECT_EQ(tC.first, compiled.nodes[nodeNamed(c.graph, "C")].orderIndex);
  EXPECT_EQ(tC.last, compiled.nodes[nodeNamed(c.graph, "D")].orderIndex);
}

TEST(Lifetimes, ASideEffectNodeKeepsItsInputAliveUntilItRuns) {
  FrameGraph g;
  const BufferHandle out = g.importBuffer("out", bufferDesc(), {1}, {}, {});
  const BufferHandle early = g.createBuffer("early", bufferDesc(kSize));
  const BufferHandle early1 = g.addNode("Produce", NodeType::Compute).write(early, Access::StorageWrite);
  BufferHandle work = g.createBuffer("w0", bufferDesc(kSize));
  work = g.addNode("Work0", NodeType::Compute).write(work, Access::StorageWrite);
  for (int i = 1; i < 4; ++i) {  // a chain that pushes the readback to a late level
    const BufferHandle next = g.createBuffer(std::string("w").append(std::to_string(i)), bufferDesc(kSize));
    NodeBuilder b = g.addNode("Work" + std::to_string(i), NodeType::Compute);
    b.read(work, Access::StorageRead);
    work = b.write(next, Access::StorageWrite);
  }
  NodeBuilder readback = g.addNode("Readback", NodeType::Transfer, QueueClass::Compute);
  readback.sideEffect();
  readback.read(early1, Access::TransferSrc);
  readback.read(work, Access::TransferSrc);
  g.addNode("Final", NodeType::Compute).write(out, Access::StorageWrite);
  const CompiledGraph compiled = compile(g);
  const Lifetime& life = compiled.lifetimes[g.resourceOf(early1)];
  EXPECT_EQ(life.last, compiled.nodes[nodeNamed(g, "Readback")].orderIndex);
  EXPECT_TRUE(compiled.resourceAlive[g.resourceOf(early1)]);
  expectAllInvariants(g, compiled, {});
}

TEST(DependentFields, ExtentAndSizeResolveAtCompileTimeThroughChains) {
  FrameGraph g;
  const TextureHandle color = g.importTexture("color", colorDesc(1920, 1080), {1}, {}, {});
  TextureDesc half = colorDesc(1, 1);
  half.extentFrom = color;
  half.extentShift = 1;
  const TextureHandle halfTex = g.createTexture("half", half);
  TextureDesc quarter = colorDesc(1, 1);
  quarter.extentFrom = halfTex;
  quarter.extentShift = 1;
  const TextureHandle quarterTex = g.createTexture("quarter", quarter);
  TextureDesc tiny = colorDesc(1, 1);
  tiny.extentFrom = color;
  tiny.extentShift = 12;  // clamps at 1
  const TextureHandle tinyTex = g.createTexture("tiny", tiny);
  const BufferHandle base = g.createBuffer("base", bufferDesc(12345));
  BufferDesc same;
  same.sizeFrom = base;
  const BufferHandle copy = g.createBuffer("copy", same);
  const CompiledGraph compiled = compile(g);
  const auto extentOf = [&](TextureHandle h) { return compiled.resources[g.resourceOf(h)].texture.extent; };
  EXPECT_EQ(extentOf(halfTex).width, 960u);
  EXPECT_EQ(extentOf(halfTex).height, 540u);
  EXPECT_EQ(extentOf(quarterTex).width, 480u);
  EXPECT_EQ(extentOf(quarterTex).height, 270u);
  EXPECT_EQ(extentOf(tinyTex).width, 1u);
  EXPECT_EQ(extentOf(tinyTex).height, 1u);
  EXPECT_EQ(compiled.resources[g.resourceOf(copy)].buffer.size, 12345u);
}

TEST(Aliasing, DisjointLifetimesShareMemory) {
  const Chain c = chainOfFour();
  const CompiledGraph compiled = compile(c.graph);
  const AliasingPlan& plan = compiled.aliasing;
  EXPECT_EQ(plan.peakBytesUnaliased, 3 * kSize);
  EXPECT_LE(plan.peakBytesAliased, 2 * kSize);  // tA and tC never live together
  EXPECT_EQ(plan.placements[c.graph.resourceOf(BufferHandle{c.graph.resources()[0].firstVersion})].heap,
            kInvalidIndex);  // the imported output
  expectAllInvariants(c.graph, compiled, {});
}

// tC takes tA's memory. A wrote tA (B only read it), so tC's first barrier must not only wait for
// A and B but make A's write available: a write still in a cache could otherwise land on tC's data.
TEST(Aliasing, ReusedMemoryMakesTheEarlierOccupantsWritesAvailable) {
  const Chain c = chainOfFour();
  const CompiledGraph compiled = compile(c.graph);
  const Placement& a = compiled.aliasing.placements[c.transients[0]];
  const Placement& cPlacement = compiled.aliasing.placements[c.transients[2]];
  ASSERT_EQ(cPlacement.heap, a.heap);
  ASSERT_EQ(cPlacement.offset, a.offset);
  EXPECT_EQ(cPlacement.aliasedAfterWrites, kAccessShaderStorageWrite);
  const auto first = std::find_if(compiled.barriers.begin(), compiled.barriers.end(),
                                  [&](const Barrier& b) { return b.resource == c.transients[2]; });
  ASSERT_NE(first, compiled.barriers.end());
  EXPECT_NE(first->srcStages & kStageComputeShader, kStageNone);
  EXPECT_EQ(first->srcAccess, kAccessShaderStorageWrite);
  expectAllInvariants(c.graph, compiled, {});
}

TEST(Aliasing, TurnedOffNothingOverlaps) {
  const Chain c = chainOfFour();
  CompileOptions options;
  options.alias = false;
  const CompiledGraph compiled = compile(c.graph, options);
  EXPECT_EQ(compiled.aliasing.peakBytesAliased, 3 * kSize);
  expectAllInvariants(c.graph, compiled, options);
}

TEST(Aliasing, IncompatibleMemoryTypesNeverShare) {
  const Chain c = chainOfFour();
  CompileOptions options;
  options.requirements = [](const ResourceDecl& decl, const ResolvedResource&) {
    // tA and tC could alias by lifetime, but their memory types are disjoint.
    return MemoryRequirements{kSize, 256, decl.name == "tA" ? 0b01u : 0b10u};
  };
  const CompiledGraph compiled = compile(c.graph, options);
  const Placement& a = compiled.aliasing.placements[c.transients[0]];
  const Placement& cc = compiled.aliasing.placements[c.transients[2]];
  EXPECT_NE(a.heap, cc.heap);
  EXPECT_EQ(compiled.aliasing.heaps[a.heap].memoryTypeBits & 0b10u, 0u);
  expectAllInvariants(c.graph, compiled, options);
}

TEST(Aliasing, RespectsLargeAlignments) {
  const Chain c = chainOfFour();
  CompileOptions options;
  options.requirements = [](const ResourceDecl& decl, const ResolvedResource&) {
    return MemoryRequirements{decl.name == "tB" ? 1000u : kSize + 100, decl.name == "tC" ? 65536u : 256u, ~0u};
  };
  const CompiledGraph compiled = compile(c.graph, options);
  EXPECT_EQ(compiled.aliasing.placements[c.transients[2]].offset % 65536, 0u);
  expectAllInvariants(c.graph, compiled, options);
}

// Two chains on two queues that never synchronise: their lifetimes are disjoint in the global
// order, but the GPU may run them at the same time, so they must not share memory.
TEST(Aliasing, UnsynchronisedQueuesNeverShareMemory) {
  FrameGraph g;
  const BufferHandle out0 = g.importBuffer("out0", bufferDesc(), {1}, {}, {});
  const BufferHandle out1 = g.importBuffer("out1", bufferDesc(), {2}, {}, {});
  auto chain = [&g](const std::string& prefix, NodeType type, int length, BufferHandle out) {
    BufferHandle previous{};
    for (int i = 0; i < length; ++i) {
      const BufferHandle t = g.createBuffer(prefix + std::to_string(i), bufferDesc(kSize));
      NodeBuilder b = g.addNode(prefix + "node" + std::to_string(i), type);
      if (previous.valid()) b.read(previous, Access::StorageRead);
      previous = b.write(t, Access::StorageWrite);
    }
    NodeBuilder last = g.addNode(prefix + "out", type);
    last.read(previous, Access::StorageRead);
    last.write(out, Access::StorageWrite);
  };
  chain("g", NodeType::Graphics, 1, out0);  // levels 0-1 on queue 0
  chain("c", NodeType::Compute, 4, out1);   // levels 0-4 on queue 1
  const CompiledGraph compiled = compile(g, queueOptions(2));
  const Placement& early = compiled.aliasing.placements[resourceNamed(g, "g0")];
  const Placement& late = compiled.aliasing.placements[resourceNamed(g, "c3")];
  const bool overlap = early.heap == late.heap && early.offset < late.offset + late.size &&
                       late.offset < early.offset + early.size;
  EXPECT_FALSE(overlap);
  expectAllInvariants(g, compiled, queueOptions(2));
}

TEST(Aliasing, UnusedResourcesGetNoPlacement) {
  FrameGraph g;
  g.createBuffer("unused", bufferDesc());
  const CompiledGraph compiled = compile(g);
  EXPECT_EQ(compiled.aliasing.placements[0].heap, kInvalidIndex);
  EXPECT_EQ(compiled.aliasing.peakBytesAliased, 0u);
  EXPECT_EQ(compiled.aliasing.peakBytesUnaliased, 0u);
}

}  // namespace
}  // namespace fgb::graph::test
