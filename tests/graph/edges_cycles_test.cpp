// Dependency edges from versions (RAW, WAR, WAW) and cycle detection that names the cycle.
#include "test_helpers.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fgb::graph::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(Edges, ReadAfterWriteOrdersProducerBeforeReaders) {
  FrameGraph graph;
  const TextureHandle out = importOutput(graph, "out");
  const TextureHandle t = graph.createTexture("t", colorDesc());
  const TextureHandle t1 = graph.addNode("P", NodeType::Compute).write(t, Access::StorageWrite);
  NodeBuilder r1 = graph.addNode("R1", NodeType::Compute);
  r1.read(t1);
  const TextureHandle out1 = r1.write(out, Access::StorageWrite);
  NodeBuilder r2 = graph.addNode("R2", NodeType::Compute);
  r2.read(t1);
  r2.write(out1, Access::StorageReadWrite);
  const CompiledGraph compiled = compile(graph);
  const NamePairs edges = edgeNames(graph, compiled.edges);
  EXPECT_TRUE(edges.contains({"P", "R1"}));
  EXPECT_TRUE(edges.contains({"P", "R2"}));
  EXPECT_TRUE(edges.contains({"R1", "R2"}));  // RAW on `out` (R2 loads what R1 wrote)
  expectAllInvariants(graph, compiled, {});
}

TEST(Edges, WriteAfterReadOrdersReadersOfAnOldVersionBeforeTheNextWriter) {
  FrameGraph graph;
  const BufferHandle b = graph.importBuffer("b", bufferDesc(), {1}, {}, {});
  const TextureHandle out = importOutput(graph, "out");
  NodeBuilder reader = graph.addNode("Reader", NodeType::Compute);
  reader.read(b, Access::StorageRead);
  const TextureHandle out1 = reader.write(out, Access::StorageWrite);
  graph.addNode("Writer", NodeType::Compute).write(b, Access::StorageWrite);
  // A later node reads the *old* version: it must still run before Writer.
  NodeBuilder late = graph.addNode("LateReader", NodeType::Compute);
  late.read(b, Access::StorageRead);
  late.write(out1, Access::StorageReadWrite);
  const CompiledGraph compiled = compile(graph);
  const NamePairs edges = edgeNames(graph, compiled.edges);
  EXPECT_TRUE(edges.contains({"Reader", "Writer"}));
  EXPECT_TRUE(edges.contains({"LateReader", "Writer"}));
  EXPECT_LT(compiled.nodes[nodeNamed(graph, "LateReader")].orderIndex,
            compiled.nodes[nodeNamed(graph, "Writer")].orderIndex);
  expectAllInvariants(graph, compiled, {});
}

TEST(Edges, WriteAfterWriteOrdersConsecutiveWriters) {
  FrameGraph graph;
  const BufferHandle b = graph.importBuffer("b", bufferDesc(), {1}, {}, {});
  const BufferHandle b1 = graph.addNode("W1", NodeType::Transfer).write(b, Access::TransferDst);
  graph.addNode("W2", NodeType::Compute, QueueClass::Transfer).write(b1, Access::StorageWrite);
  const CompiledGraph compiled = compile(graph);
  EXPECT_EQ(edgeNames(graph, compiled.edges), (NamePairs{{"W1", "W2"}}));
}

TEST(Edges, SeveralResourcesBetweenTwoNodesGiveOneEdgeAndReadWriteNoSelfEdge) {
  FrameGraph graph;
  const TextureHandle out = importOutput(graph, "out");
  const BufferHandle a = graph.createBuffer("a", bufferDesc());
  const BufferHandle b = graph.createBuffer("b", bufferDesc());
  NodeBuilder producer = graph.addNode("P", NodeType::Compute);
  const BufferHandle a1 = producer.write(a, Access::StorageWrite);
  const BufferHandle b1 = producer.write(b, Access::StorageWrite);
  NodeBuilder consumer = graph.addNode("C", NodeType::Compute);
  consumer.read(a1, Access::StorageRead);
  consumer.write(b1, Access::StorageReadWrite);
  consumer.write(out, Access::StorageWrite);
  const CompiledGraph compiled = compile(graph);
  EXPECT_EQ(edgeNames(graph, compiled.edges), (NamePairs{{"P", "C"}}));
}

// P writes t; R reads it; W1 overwrites t but nobody reads that (culled); W2 overwrites again and
// a side effect reads it. R must still run before W2 even though the WAR/WAW chain went through W1.
TEST(Edges, OrderingSurvivesACulledWriterInBetween) {
  FrameGraph graph;
  const TextureHandle out = importOutput(graph, "out");
  const TextureHandle t = graph.createTexture("t", colorDesc());
  const TextureHandle t1 = graph.addNode("P", NodeType::Compute).write(t, Access::StorageWrite);
  NodeBuilder r = graph.addNode("R", NodeType::Compute);
  r.read(t1);
  r.write(out, Access::StorageWrite);
  const TextureHandle t2 = graph.addNode("W1", NodeType::Compute).write(t1, Access::StorageWrite);
  const TextureHandle t3 = graph.addNode("W2", NodeType::Compute).write(t2, Access::StorageWrite);
  graph.addNode("Dump", NodeType::Compute).sideEffect().read(t3, Access::StorageRead);
  const CompiledGraph compiled = compile(graph);
  EXPECT_TRUE(compiled.nodes[nodeNamed(graph, "W1")].culled);
  EXPECT_LT(compiled.nodes[nodeNamed(graph, "R")].orderIndex, compiled.nodes[nodeNamed(graph, "W2")].orderIndex);
  EXPECT_LT(compiled.nodes[nodeNamed(graph, "P")].orderIndex, compiled.nodes[nodeNamed(graph, "W2")].orderIndex);
  expectAllInvariants(graph, compiled, {});
}

// A reads the old version of r and also reads x, which the writer of r's next version produced:
// A -> W (WAR) and W -> A (RAW) close a cycle.
TEST(Cycles, TwoNodeCycleThroughAnOldVersionNamesBothNodes) {
  FrameGraph graph;
  const BufferHandle r = graph.importBuffer("r", bufferDesc(), {1}, {}, {});
  const BufferHandle x = graph.createBuffer("x", bufferDesc());
  NodeBuilder writer = graph.addNode("Writer", NodeType::Compute);
  writer.write(r, Access::StorageWrite);
  const BufferHandle x1 = writer.write(x, Access::StorageWrite);
  const BufferHandle y = graph.createBuffer("y", bufferDesc());
  const BufferHandle y1 = graph.addNode("Unrelated", NodeType::Compute).write(y, Access::StorageWrite);
  graph.addNode("Bystander", NodeType::Compute).sideEffect().read(y1, Access::StorageRead);
  NodeBuilder a = graph.addNode("Aaa", NodeType::Compute);
  a.read(r, Access::StorageRead);
  a.read(x1, Access::StorageRead);
  a.sideEffect();
  std::string message;
  try {
    (void)compile(graph);
  } catch (const GraphError& error) {
    message = error.what();
  }
  EXPECT_THAT(message, HasSubstr("cycle"));
  EXPECT_THAT(message, HasSubstr("Writer"));
  EXPECT_THAT(message, HasSubstr("Aaa"));
  EXPECT_THAT(message, Not(HasSubstr("Bystander")));
}

TEST(Cycles, ThreeNodeCycleNamesEveryNodeOnIt) {
  FrameGraph graph;
  const BufferHandle r = graph.importBuffer("r", bufferDesc(), {1}, {}, {});
  const BufferHandle x = graph.createBuffer("x", bufferDesc());
  const BufferHandle y = graph.createBuffer("y", bufferDesc());
  NodeBuilder w = graph.addNode("Wr", NodeType::Compute);
  w.write(r, Access::StorageWrite);
  const BufferHandle x1 = w.write(x, Access::StorageWrite);
  NodeBuilder m = graph.addNode("Mid", NodeType::Compute);
  m.read(x1, Access::StorageRead);
  const BufferHandle y1 = m.write(y, Access::StorageWrite);
  NodeBuilder last = graph.addNode("Last", NodeType::Compute);
  last.read(y1, Access::StorageRead);
  last.read(r, Access::Uniform);  // old version of r: Last -> Wr
  last.sideEffect();
  try {
    (void)compile(graph);
    ADD_FAILURE() << "cycle not detected";
  } catch (const GraphError& error) {
    const std::string message = error.what();
    EXPECT_THAT(message, HasSubstr("Wr"));
    EXPECT_THAT(message, HasSubstr("Mid"));
    EXPECT_THAT(message, HasSubstr("Last"));
  }
}

}  // namespace
}  // namespace fgb::graph::test
