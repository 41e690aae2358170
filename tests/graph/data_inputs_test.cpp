// dataInputs: the read-after-write edges of a declaration (per-pass goldens' "inputs").
#include <gtest/gtest.h>

#include <fgb/graph/data_inputs.hpp>

#include "test_helpers.hpp"

namespace fgb::graph::test {
namespace {

TEST(DataInputs, ReadsAndLoadsAreInputsButWriteAfterReadIsNot) {
  FrameGraph g;
  BufferHandle a = g.createBuffer("a", bufferDesc());
  BufferHandle b = g.createBuffer("b", bufferDesc());
  NodeBuilder first = g.addNode("first", NodeType::Compute);
  a = first.write(a, Access::StorageWrite);
  NodeBuilder second = g.addNode("second", NodeType::Compute);
  second.read(a, Access::StorageRead);
  b = second.write(b, Access::StorageWrite);
  NodeBuilder third = g.addNode("third", NodeType::Compute);  // overwrites a after second read it
  a = third.write(a, Access::StorageReadWrite);               // loads first's version
  NodeBuilder fourth = g.addNode("fourth", NodeType::Compute);
  fourth.read(a, Access::StorageRead);
  fourth.read(b, Access::StorageRead);
  fourth.sideEffect();
  const auto inputs = dataInputs(g);
  ASSERT_EQ(inputs.size(), 4u);
  EXPECT_TRUE(inputs[0].empty());
  EXPECT_EQ(inputs[1], (std::vector<uint32_t>{0}));
  EXPECT_EQ(inputs[2], (std::vector<uint32_t>{0}));     // not 1: a write after 1's read is no data
  EXPECT_EQ(inputs[3], (std::vector<uint32_t>{1, 2}));  // a from third, b from second
}

}  // namespace
}  // namespace fgb::graph::test
