// Critical paths over compiled schedules: the predecessors a schedule gives each node, and each
// node's share of the longest chain of costs.
#include <gtest/gtest.h>

#include <fgb/graph/critical_path.hpp>

#include "test_helpers.hpp"

namespace fgb::graph::test {
namespace {

TEST(CriticalPath, SharesOfAChainAndAParallelBranch) {
  // 0 -> 1 -> 3 and 0 -> 2 -> 3: 1 (4 ms) is on the path, 2 (1 ms) is not.
  const std::vector<std::vector<uint32_t>> predecessors{{}, {0}, {0}, {1, 2}};
  const std::vector<double> costs{1.0, 4.0, 1.0, 2.0};
  const CriticalPath path = criticalPath(predecessors, costs);
  EXPECT_DOUBLE_EQ(path.lengthMs, 7.0);
  EXPECT_DOUBLE_EQ(path.shareOfPath[0], 1.0 / 7.0);
  EXPECT_DOUBLE_EQ(path.shareOfPath[1], 3.0 / 7.0);  // without it, 0 -> 2 -> 3 takes 4 ms
  EXPECT_DOUBLE_EQ(path.shareOfPath[2], 0.0);
  EXPECT_DOUBLE_EQ(path.shareOfPath[3], 2.0 / 7.0);
  EXPECT_EQ(path.onPath, (std::vector<bool>{true, true, false, true}));
}

TEST(CriticalPath, EqualBranchesHideEachOther) {
  const CriticalPath path = criticalPath({{}, {}}, std::vector<double>{2.0, 2.0});
  EXPECT_DOUBLE_EQ(path.lengthMs, 2.0);
  EXPECT_DOUBLE_EQ(path.shareOfPath[0], 0.0);  // the other one still takes 2 ms
  EXPECT_TRUE(path.onPath[0] && path.onPath[1]);
}

TEST(CriticalPath, ACycleIsRefused) {
  EXPECT_THROW(criticalPath({{1}, {0}}, std::vector<double>{1, 1}), std::invalid_argument);
}

BufferHandle stage(FrameGraph& g, const std::string& name, NodeType type, std::initializer_list<BufferHandle> in) {
  const BufferHandle out = g.createBuffer(name + ".out", bufferDesc());
  NodeBuilder b = g.addNode(name, type);
  for (BufferHandle h : in) b.read(h, Access::StorageRead);
  return b.write(out, Access::StorageWrite);
}

TEST(SchedulePredecessors, QueueOrderAndSemaphoreWaits) {
  // Graphics A, compute C (independent of A), graphics B reads C: on two queues, B's submit waits
  // for C's; on one queue every node follows the one before it.
  FrameGraph g;
  const BufferHandle a = stage(g, "A", NodeType::Graphics, {});
  const BufferHandle c = stage(g, "C", NodeType::Compute, {});
  const BufferHandle b = stage(g, "B", NodeType::Graphics, {a, c});
  g.addNode("Sink", NodeType::Graphics).sideEffect().read(b, Access::StorageRead);
  const uint32_t nodeA = nodeNamed(g, "A"), nodeB = nodeNamed(g, "B"), nodeC = nodeNamed(g, "C");

  const auto two = schedulePredecessors(compile(g, queueOptions(2)));
  const auto contains = [](const std::vector<uint32_t>& list, uint32_t node) {
    return std::find(list.begin(), list.end(), node) != list.end();
  };
  EXPECT_TRUE(contains(two[nodeB], nodeA));
  EXPECT_TRUE(contains(two[nodeB], nodeC));
  EXPECT_TRUE(two[nodeC].empty());  // alone on the compute queue, waiting for nothing

  // With costs A 1, C 3, B 1: the chain C -> B -> Sink is the critical one on two queues.
  std::vector<double> costs(4, 1.0);
  costs[nodeC] = 3.0;
  const CriticalPath overlapped = criticalPath(two, costs);
  EXPECT_DOUBLE_EQ(overlapped.lengthMs, 5.0);
  EXPECT_DOUBLE_EQ(overlapped.shareOfPath[nodeA], 0.0);
  EXPECT_DOUBLE_EQ(overlapped.shareOfPath[nodeC], 2.0 / 5.0);  // without it, A -> B -> Sink: 3 ms

  const CriticalPath serial = criticalPath(schedulePredecessors(compile(g, queueOptions(1))), costs);
  EXPECT_DOUBLE_EQ(serial.lengthMs, 6.0);  // one queue: everything in a row
  EXPECT_DOUBLE_EQ(serial.shareOfPath[nodeA], 1.0 / 6.0);
}

}  // namespace
}  // namespace fgb::graph::test
