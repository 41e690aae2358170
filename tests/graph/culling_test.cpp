// Culling by flood fill from imported resources and side-effect nodes, with a reason per node.
#include "test_helpers.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace fgb::graph::test {
namespace {

struct Pipeline {
  FrameGraph graph;
  CompiledGraph compiled;
};

// Shadow -> Light -> (out); Debug writes a transient nobody reads; Probe only reads.
Pipeline declareWithDeadBranches(bool cull) {
  Pipeline p;
  FrameGraph& g = p.graph;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle shadow = g.createTexture("shadow", colorDesc(512, 512, Format::D32Sfloat));
  const TextureHandle debug = g.createTexture("debug-view", colorDesc());
  const TextureHandle shadow1 = g.addNode("Shadow", NodeType::Graphics).setDepthStencil(shadow);
  NodeBuilder light = g.addNode("Light", NodeType::Graphics);
  light.read(shadow1);
  light.addColorTarget(out);
  NodeBuilder dbg = g.addNode("Debug", NodeType::Compute);
  dbg.read(shadow1);
  dbg.write(debug, Access::StorageWrite);
  g.addNode("Probe", NodeType::Compute).read(shadow1);
  CompileOptions options;
  options.cull = cull;
  p.compiled = compile(g, options);
  return p;
}

TEST(Culling, KeepsExactlyTheWorkThatReachesAnImportedResource) {
  const Pipeline p = declareWithDeadBranches(true);
  EXPECT_FALSE(p.compiled.nodes[nodeNamed(p.graph, "Shadow")].culled);
  EXPECT_FALSE(p.compiled.nodes[nodeNamed(p.graph, "Light")].culled);
  EXPECT_TRUE(p.compiled.nodes[nodeNamed(p.graph, "Debug")].culled);
  EXPECT_TRUE(p.compiled.nodes[nodeNamed(p.graph, "Probe")].culled);
  EXPECT_EQ(p.compiled.order.size(), 2u);
  expectAllInvariants(p.graph, p.compiled, {});
}

TEST(Culling, SaysWhyEachNodeWasCulled) {
  const Pipeline p = declareWithDeadBranches(true);
  const NodeInfo& debug = p.compiled.nodes[nodeNamed(p.graph, "Debug")];
  EXPECT_EQ(debug.reason, CullReason::OutputsUnread);
  EXPECT_EQ(cullDiagnostic(p.graph, p.compiled, nodeNamed(p.graph, "Debug")),
            "writes 'debug-view' v5, none imported; nothing reads them");
  const NodeInfo& probe = p.compiled.nodes[nodeNamed(p.graph, "Probe")];
  EXPECT_EQ(probe.reason, CullReason::NoOutputs);
  EXPECT_EQ(cullDiagnostic(p.graph, p.compiled, nodeNamed(p.graph, "Probe")), "declares no writes and no side effect");
  EXPECT_EQ(p.compiled.nodes[nodeNamed(p.graph, "Light")].reason, CullReason::Alive);
  EXPECT_EQ(cullDiagnostic(p.graph, p.compiled, nodeNamed(p.graph, "Light")), "");
}

TEST(Culling, CulledResourcesAreNotAliveAndGetNoMemory) {
  const Pipeline p = declareWithDeadBranches(true);
  const uint32_t debugView = resourceNamed(p.graph, "debug-view");
  EXPECT_FALSE(p.compiled.resourceAlive[debugView]);
  EXPECT_FALSE(p.compiled.lifetimes[debugView].used());
  EXPECT_EQ(p.compiled.aliasing.placements[debugView].heap, kInvalidIndex);
}

TEST(Culling, CanBeTurnedOff) {
  const Pipeline p = declareWithDeadBranches(false);
  for (const NodeInfo& info : p.compiled.nodes) EXPECT_FALSE(info.culled);
  EXPECT_EQ(p.compiled.order.size(), 4u);
  CompileOptions options;
  options.cull = false;
  expectAllInvariants(p.graph, p.compiled, options);
}

// Culled nodes sit between alive ones in declaration order and share their levels (Debug and
// Probe read what Shadow wrote, like Light); the sort sets them aside without a branch. Their
// NodeInfo must say they have no place in the schedule, even where the compile before (culling
// off) left one in the pooled storage it reuses.
TEST(Culling, ACulledNodeHasNoPlaceInTheSchedule) {
  { const Pipeline everything = declareWithDeadBranches(false); }  // hands its storage to the pool
  const Pipeline p = declareWithDeadBranches(true);
  for (const char* name : {"Debug", "Probe"}) {
    const NodeInfo& info = p.compiled.nodes[nodeNamed(p.graph, name)];
    EXPECT_EQ(info.level, 0u) << name;
    EXPECT_EQ(info.orderIndex, kInvalidIndex) << name;
    EXPECT_EQ(info.step, kInvalidIndex) << name;
    EXPECT_EQ(info.submit, kInvalidIndex) << name;
  }
  EXPECT_EQ(p.compiled.order, (std::vector<uint32_t>{nodeNamed(p.graph, "Shadow"), nodeNamed(p.graph, "Light")}));
  EXPECT_EQ(p.compiled.nodes[nodeNamed(p.graph, "Light")].orderIndex, 1u);
  expectAllInvariants(p.graph, p.compiled, {});
}

TEST(Culling, ACulledConsumerDoesNotKeepItsProducerAlive) {
  FrameGraph g;
  const BufferHandle a = g.createBuffer("a", bufferDesc());
  const BufferHandle b = g.createBuffer("b", bufferDesc());
  const BufferHandle a1 = g.addNode("Producer", NodeType::Compute).write(a, Access::StorageWrite);
  NodeBuilder consumer = g.addNode("Consumer", NodeType::Compute);
  consumer.read(a1, Access::StorageRead);
  consumer.write(b, Access::StorageWrite);
  const CompiledGraph compiled = compile(g);
  EXPECT_TRUE(compiled.nodes[0].culled);
  EXPECT_TRUE(compiled.nodes[1].culled);
  EXPECT_EQ(cullDiagnostic(g, compiled, 0), "writes 'a' v2, none imported; read only by culled nodes 'Consumer'");
  EXPECT_TRUE(compiled.order.empty());
  EXPECT_TRUE(compiled.steps.empty());
}

TEST(Culling, ASideEffectNodeLivesAndKeepsItsInputsProducersAlive) {
  FrameGraph g;
  const BufferHandle stats = g.createBuffer("stats", bufferDesc());
  const BufferHandle unrelated = g.createBuffer("unrelated", bufferDesc());
  const BufferHandle stats1 = g.addNode("Count", NodeType::Compute).write(stats, Access::StorageWrite);
  g.addNode("Other", NodeType::Compute).write(unrelated, Access::StorageWrite);
  g.addNode("Readback", NodeType::Transfer).sideEffect().read(stats1, Access::TransferSrc);
  const CompiledGraph compiled = compile(g);
  EXPECT_FALSE(compiled.nodes[nodeNamed(g, "Count")].culled);
  EXPECT_FALSE(compiled.nodes[nodeNamed(g, "Readback")].culled);
  EXPECT_TRUE(compiled.nodes[nodeNamed(g, "Other")].culled);
  expectAllInvariants(g, compiled, {});
}

TEST(Culling, WritingAnImportedBufferKeepsANodeEvenIfNobodyReadsIt) {
  FrameGraph g;
  const BufferHandle imported = g.importBuffer("history", bufferDesc(), {9}, {}, {});
  g.addNode("Store", NodeType::Compute).write(imported, Access::StorageWrite);
  const CompiledGraph compiled = compile(g);
  EXPECT_FALSE(compiled.nodes[0].culled);
}

}  // namespace
}  // namespace fgb::graph::test
