// Queue assignment, SSIS pruning (thesis Algorithm 3) giving G*, submits and timeline values.
#include "test_helpers.hpp"

#include <gtest/gtest.h>

namespace fgb::graph::test {
namespace {

// Declares `name` of `type` reading the given buffers and writing one new transient.
BufferHandle stage(FrameGraph& g, const std::string& name, NodeType type, std::initializer_list<BufferHandle> in,
                   bool sink = false) {
  const BufferHandle out = g.createBuffer(name + ".out", bufferDesc());
  NodeBuilder b = g.addNode(name, type);
  for (BufferHandle h : in) b.read(h, type == NodeType::Transfer ? Access::TransferSrc : Access::StorageRead);
  const BufferHandle written = b.write(out, type == NodeType::Transfer ? Access::TransferDst : Access::StorageWrite);
  if (sink) b.sideEffect();
  return written;
}

TEST(Queues, ClassesMapToQueuesAndOverridesAreHonoured) {
  FrameGraph g;
  stage(g, "gfx", NodeType::Graphics, {}, true);
  stage(g, "cmp", NodeType::Compute, {}, true);
  stage(g, "xfer", NodeType::Transfer, {}, true);
  const BufferHandle out = g.createBuffer("o", bufferDesc());
  g.addNode("cmp-on-gfx", NodeType::Compute, QueueClass::Graphics).sideEffect().write(out, Access::StorageWrite);
  const CompiledGraph three = compile(g, queueOptions(3));
  EXPECT_EQ(three.nodes[nodeNamed(g, "gfx")].queue, 0u);
  EXPECT_EQ(three.nodes[nodeNamed(g, "cmp")].queue, 1u);
  EXPECT_EQ(three.nodes[nodeNamed(g, "xfer")].queue, 2u);
  EXPECT_EQ(three.nodes[nodeNamed(g, "cmp-on-gfx")].queue, 0u);
  const CompiledGraph one = compile(g, queueOptions(1));
  for (uint32_t n : one.order) EXPECT_EQ(one.nodes[n].queue, 0u);
}

TEST(Ssis, OneQueueHasNoSyncEdgesAndOneSubmitWithoutWaits) {
  FrameGraph g;
  const BufferHandle a = stage(g, "A", NodeType::Compute, {});
  const BufferHandle b = stage(g, "B", NodeType::Transfer, {a});
  stage(g, "C", NodeType::Graphics, {a, b}, true);
  const CompiledGraph compiled = compile(g, queueOptions(1));
  EXPECT_TRUE(compiled.syncEdges.empty());
  ASSERT_EQ(compiled.submits.size(), 1u);
  EXPECT_TRUE(compiled.submits[0].waits.empty());
  EXPECT_EQ(compiled.submits[0].signalValue, 1u);
  EXPECT_EQ(compiled.submits[0].stepCount, 3u);
  EXPECT_EQ(compiled.submitsPerQueue, (std::vector<uint32_t>{1}));
  for (uint32_t i = 0; i < compiled.steps.size(); ++i) EXPECT_EQ(compiled.steps[i].node, compiled.order[i]);
}

// Y (queue 1) depends on A (queue 0) and on X (queue 1), which already waited for A: queue order
// X -> Y makes A -> Y redundant.
TEST(Ssis, PrunesAnEdgeCoveredBySameQueueOrder) {
  FrameGraph g;
  const BufferHandle a = stage(g, "A", NodeType::Graphics, {});
  const BufferHandle x = stage(g, "X", NodeType::Compute, {a});
  stage(g, "Y", NodeType::Compute, {a, x}, true);
  const CompiledGraph compiled = compile(g, queueOptions(2));
  EXPECT_EQ(edgeNames(g, compiled.edges), (NamePairs{{"A", "X"}, {"A", "Y"}, {"X", "Y"}}));
  EXPECT_EQ(edgeNames(g, compiled.syncEdges), (NamePairs{{"A", "X"}}));
  expectAllInvariants(g, compiled, queueOptions(2));
}

// C (queue 1) depends on A and B (queue 0, A before B): waiting for B covers A.
TEST(Ssis, PrunesAnEdgeCoveredByALaterNodeOnTheSourceQueue) {
  FrameGraph g;
  const BufferHandle a = stage(g, "A", NodeType::Graphics, {});
  const BufferHandle b = stage(g, "B", NodeType::Graphics, {a});
  stage(g, "C", NodeType::Compute, {a, b}, true);
  const CompiledGraph compiled = compile(g, queueOptions(2));
  EXPECT_EQ(edgeNames(g, compiled.syncEdges), (NamePairs{{"B", "C"}}));
}

// Three queues: T (transfer) needs G (graphics) and C (compute), and C already waited for G.
TEST(Ssis, PrunesTransitivelyAcrossThreeQueues) {
  FrameGraph g;
  const BufferHandle gfx = stage(g, "G", NodeType::Graphics, {});
  const BufferHandle cmp = stage(g, "C", NodeType::Compute, {gfx});
  stage(g, "T", NodeType::Transfer, {gfx, cmp}, true);
  const CompiledGraph compiled = compile(g, queueOptions(3));
  EXPECT_EQ(edgeNames(g, compiled.syncEdges), (NamePairs{{"G", "C"}, {"C", "T"}}));
  expectAllInvariants(g, compiled, queueOptions(3));
}

TEST(Ssis, KeepsEdgesThatAreNotRedundant) {
  FrameGraph g;
  const BufferHandle gfx = stage(g, "G", NodeType::Graphics, {});
  const BufferHandle cmp = stage(g, "C", NodeType::Compute, {});
  stage(g, "T", NodeType::Transfer, {gfx, cmp}, true);
  const CompiledGraph compiled = compile(g, queueOptions(3));
  EXPECT_EQ(edgeNames(g, compiled.syncEdges), (NamePairs{{"G", "T"}, {"C", "T"}}));
}

// A (queue 0) -> X (queue 1) -> B (queue 0): queue 0 is split after A's level; B waits for X and X
// for A; signal values are 1-based per queue.
TEST(Submits, PlacedAfterSignallingLevelsWithTimelineValues) {
  FrameGraph g;
  const BufferHandle a = stage(g, "A", NodeType::Graphics, {});
  const BufferHandle x = stage(g, "X", NodeType::Compute, {a});
  stage(g, "B", NodeType::Graphics, {x}, true);
  const CompiledGraph c = compile(g, queueOptions(2));
  ASSERT_EQ(c.submits.size(), 3u);
  EXPECT_EQ(c.submitsPerQueue, (std::vector<uint32_t>{2, 1}));
  const Submit& first = c.submits[0];
  const Submit& second = c.submits[1];
  const Submit& compute = c.submits[2];
  EXPECT_EQ(first.queue, 0u);
  EXPECT_EQ(first.signalValue, 1u);
  EXPECT_EQ(first.stepCount, 1u);
  EXPECT_TRUE(first.waits.empty());
  EXPECT_EQ(c.steps[first.firstStep].node, nodeNamed(g, "A"));
  EXPECT_EQ(second.signalValue, 2u);
  ASSERT_EQ(second.waits.size(), 1u);
  EXPECT_EQ(second.waits[0].queue, 1u);
  EXPECT_EQ(second.waits[0].value, 1u);
  EXPECT_EQ(compute.queue, 1u);
  EXPECT_EQ(compute.signalValue, 1u);
  ASSERT_EQ(compute.waits.size(), 1u);
  EXPECT_EQ(compute.waits[0].queue, 0u);
  EXPECT_EQ(compute.waits[0].value, 1u);
  EXPECT_EQ(c.nodes[nodeNamed(g, "B")].submit, 1u);
  expectAllInvariants(g, c, queueOptions(2));
}

TEST(Submits, IndependentQueuesDoNotWaitOnEachOther) {
  FrameGraph g;
  stage(g, "G", NodeType::Graphics, {}, true);
  stage(g, "C", NodeType::Compute, {}, true);
  stage(g, "T", NodeType::Transfer, {}, true);
  const CompiledGraph c = compile(g, queueOptions(3));
  EXPECT_EQ(c.submits.size(), 3u);
  for (const Submit& s : c.submits) EXPECT_TRUE(s.waits.empty());
  EXPECT_TRUE(c.syncEdges.empty());
}

// No sync edges: each queue's steps are one submit however many levels they span, and a queue
// with no steps gets none.
TEST(Submits, WithoutSyncEdgesEachQueueIsOneSubmit) {
  FrameGraph g;
  const BufferHandle g1 = stage(g, "G1", NodeType::Graphics, {});
  const BufferHandle g2 = stage(g, "G2", NodeType::Graphics, {g1});
  stage(g, "G3", NodeType::Graphics, {g2}, true);
  const BufferHandle c1 = stage(g, "C1", NodeType::Compute, {});
  stage(g, "C2", NodeType::Compute, {c1}, true);
  const CompiledGraph c = compile(g, queueOptions(3));
  EXPECT_TRUE(c.syncEdges.empty());
  ASSERT_EQ(c.submits.size(), 2u);
  EXPECT_EQ(c.submitsPerQueue, (std::vector<uint32_t>{1, 1, 0}));
  for (uint32_t i = 0; i < 2; ++i) {
    const Submit& submit = c.submits[i];
    EXPECT_EQ(submit.queue, i);
    EXPECT_EQ(submit.signalValue, 1u);
    EXPECT_TRUE(submit.waits.empty());
    EXPECT_EQ(submit.stepCount, i == 0 ? 3u : 2u);
    for (uint32_t step = submit.firstStep; step < submit.firstStep + submit.stepCount; ++step) {
      EXPECT_EQ(c.nodes[c.steps[step].node].submit, i);
    }
  }
  expectAllInvariants(g, c, queueOptions(3));
}

}  // namespace
}  // namespace fgb::graph::test
