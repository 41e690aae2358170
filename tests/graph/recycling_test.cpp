// A compile depends on its graph and options only: not on earlier compiles on the thread, nor on
// whether the graph was copied or moved.
#include "flatten.hpp"
#include "random_graph.hpp"
#include "test_helpers.hpp"

#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace fgb::graph::test {
namespace {

// A random declaration that compiles (no cycle), and the options to compile it with.
struct Case {
  RandomGraph random;
  CompileOptions options;
};

Case compilableCase(uint32_t firstSeed, uint32_t nodes, uint32_t queues) {
  for (uint32_t seed = firstSeed;; ++seed) {
    Case c{makeRandomGraph(seed, {.nodes = nodes, .queueCount = queues}), randomCompileOptions(queues)};
    try {
      (void)compile(*c.random.graph, c.options);
      return c;
    } catch (const GraphError&) {  // a cycle through an old-version read: try the next seed
    }
  }
}

TEST(Recycling, ACompileGivesTheSameResultWhateverCompiledBefore) {
  const Case small = compilableCase(11, 25, 3);
  // On a fresh thread: the reference result.
  Flattened fresh;
  std::thread([&] { fresh = flatten(*small.random.graph, compile(*small.random.graph, small.options)); }).join();
  // Here, after larger graphs with other shapes, queue counts and culled nodes.
  for (uint32_t queues = 1; queues <= 3; ++queues) {
    const Case large = compilableCase(1000 + queues, 60, queues);
    { const CompiledGraph before = compile(*large.random.graph, large.options); }
    EXPECT_EQ(flatten(*small.random.graph, compile(*small.random.graph, small.options)), fresh)
        << "after a " << queues << "-queue graph";
  }
}

TEST(Recycling, MovedAndCopiedGraphsCompileAlikeAndAMovedFromGraphCanBeRedeclared) {
  const Case c = compilableCase(77, 30, 2);
  const Flattened expected = flatten(*c.random.graph, compile(*c.random.graph, c.options));
  FrameGraph copy = *c.random.graph;
  EXPECT_EQ(flatten(copy, compile(copy, c.options)), expected);
  FrameGraph moved = std::move(copy);
  EXPECT_EQ(flatten(moved, compile(moved, c.options)), expected);
  CompiledGraph compiled = compile(moved, c.options);
  const CompiledGraph compiledCopy = compiled;
  const CompiledGraph compiledMoved = std::move(compiled);
  EXPECT_EQ(flatten(moved, compiledCopy), expected);
  EXPECT_EQ(flatten(moved, compiledMoved), expected);

  // `copy` was moved from: it is empty, and declaring into it works like into a new graph.
  ASSERT_TRUE(copy.nodes().empty());
  const BufferHandle out = copy.importBuffer("out", bufferDesc(), {1}, {}, {});
  copy.addNode("Write", NodeType::Compute).write(out, Access::StorageWrite);
  const CompiledGraph single = compile(copy);
  ASSERT_EQ(single.order.size(), 1u);
  EXPECT_EQ(usesOf(copy, 0).size(), 1u);
}

}  // namespace
}  // namespace fgb::graph::test
