// Longest-path dependency levels and the topological order stable-sorted by level, including the
// thesis' 13-node example whose sorted levels are 0 0 0 1 1 1 2 2 3 3 4 4 4.
#include "test_helpers.hpp"

#include <gtest/gtest.h>

#include <map>

namespace fgb::graph::test {
namespace {

// Declares a node that reads the outputs of `inputs` and writes one new transient (or is a side
// effect when `output` is false). Returns its output.
struct Dag {
  FrameGraph graph;
  std::map<std::string, BufferHandle> outputs;

  void node(const std::string& name, std::initializer_list<const char*> inputs, bool sink = false) {
    const BufferHandle buffer = graph.createBuffer(name + ".out", bufferDesc(1024));
    NodeBuilder builder = graph.addNode(name, NodeType::Compute);
    for (const char* input : inputs) builder.read(outputs.at(input), Access::StorageRead);
    outputs[name] = builder.write(buffer, Access::StorageWrite);
    if (sink) builder.sideEffect();
  }
};

// The thesis' example shape: three sources, then 3, 2, 2 and 3 nodes per level. Declared in an
// interleaved (but valid) order so the sort has work to do.
Dag thesisExample() {
  Dag d;
  d.node("A", {});
  d.node("D", {"A"});
  d.node("B", {});
  d.node("E", {"B"});
  d.node("G", {"D", "E"});
  d.node("I", {"G"});
  d.node("K", {"I"}, true);
  d.node("C", {});
  d.node("F", {"C", "A"});
  d.node("H", {"F"});
  d.node("J", {"H", "G"});
  d.node("L", {"J"}, true);
  d.node("M", {"I", "J"}, true);
  return d;
}

TEST(Levels, ThesisExampleSortsToTheDocumentedLevels) {
  const Dag d = thesisExample();
  const CompiledGraph compiled = compile(d.graph);
  ASSERT_EQ(compiled.order.size(), 13u);
  std::vector<uint32_t> levels;
  for (uint32_t node : compiled.order) levels.push_back(compiled.nodes[node].level);
  EXPECT_EQ(levels, (std::vector<uint32_t>{0, 0, 0, 1, 1, 1, 2, 2, 3, 3, 4, 4, 4}));
  const std::map<std::string, uint32_t> expected{{"A", 0}, {"B", 0}, {"C", 0}, {"D", 1}, {"E", 1},
                                                 {"F", 1}, {"G", 2}, {"H", 2}, {"I", 3}, {"J", 3},
                                                 {"K", 4}, {"L", 4}, {"M", 4}};
  for (const auto& [name, level] : expected) {
    EXPECT_EQ(compiled.nodes[nodeNamed(d.graph, name)].level, level) << name;
  }
  expectAllInvariants(d.graph, compiled, {});
}

TEST(Levels, AreLongestNotShortestPaths) {
  Dag d;
  d.node("S", {});
  d.node("X", {"S"});
  d.node("Y", {"X"});
  d.node("Z", {"S", "Y"}, true);  // shortest path from S is 1, longest is 3
  const CompiledGraph compiled = compile(d.graph);
  EXPECT_EQ(compiled.nodes[nodeNamed(d.graph, "Z")].level, 3u);
  EXPECT_EQ(compiled.order.back(), nodeNamed(d.graph, "Z"));
}

TEST(Levels, OrderIndexIsThePositionInOrder) {
  const Dag d = thesisExample();
  const CompiledGraph compiled = compile(d.graph);
  for (uint32_t i = 0; i < compiled.order.size(); ++i) EXPECT_EQ(compiled.nodes[compiled.order[i]].orderIndex, i);
}

TEST(Levels, CulledNodesDoNotRaiseLevels) {
  Dag d;
  d.node("Dead1", {});
  d.node("Dead2", {"Dead1"});
  d.node("Src", {});
  // Sink reads Src only; the dead chain has nothing to do with it.
  d.node("Sink", {"Src"}, true);
  const CompiledGraph compiled = compile(d.graph);
  EXPECT_TRUE(compiled.nodes[nodeNamed(d.graph, "Dead2")].culled);
  EXPECT_EQ(compiled.nodes[nodeNamed(d.graph, "Sink")].level, 1u);
}

TEST(Levels, IndependentNodesShareLevelZero) {
  Dag d;
  d.node("P", {}, true);
  d.node("Q", {}, true);
  d.node("R", {}, true);
  const CompiledGraph compiled = compile(d.graph);
  for (uint32_t node : compiled.order) EXPECT_EQ(compiled.nodes[node].level, 0u);
  EXPECT_TRUE(compiled.edges.empty());
}

}  // namespace
}  // namespace fgb::graph::test
