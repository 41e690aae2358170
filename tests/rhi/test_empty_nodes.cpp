// Nodes whose job records nothing cost no commands: the executor defers a node's barriers, label
// and timestamps until its first command, merges the deferred barriers into the next node that
// records work, skips barriers on graph memory no recorded command has touched, and submits a
// batch of such nodes without a command buffer. Synchronization validation must stay silent, the
// data must still arrive, and an empty node must report no GPU time.
#include "gpu_support.hpp"

#include <algorithm>

namespace fgb::test {
namespace {

constexpr uint32_t kWords = 64;

class EmptyNodes : public GpuTest, public testing::WithParamInterface<uint32_t> {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    readback_ = readbackBuffer("readback", kWords * 4);
  }

  // Transfer "Fill 7" writes a transient; then `emptyNodes` nodes alternating compute and transfer
  // each write it again (WAW) but record nothing; "Copy out" reads it (RAW). The empty nodes'
  // barriers merge into the copy's, which must still wait for the fill.
  std::unique_ptr<rhi::ExecutableGraph> build(uint32_t emptyNodes, uint32_t queues) {
    graph::FrameGraph g;
    graph::BufferHandle words = g.createBuffer("words", {kWords * 4});
    {
      auto node = g.addNode("Fill 7", graph::NodeType::Transfer);
      words = node.write(words, graph::Access::TransferDst);
      node.setJob([=](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().fillBuffer(ctx.buffer(words), 0, kWords * 4, 7);
      });
    }
    for (uint32_t i = 0; i < emptyNodes; ++i) {
      const bool compute = i % 2 == 0;
      auto node = g.addNode("Empty " + std::to_string(i), compute ? graph::NodeType::Compute : graph::NodeType::Transfer);
      words = node.write(words, compute ? graph::Access::StorageReadWrite : graph::Access::TransferDst);
      node.sideEffect();  // keeps the node (a TransferDst write would otherwise cull the fill)
      node.setJob([](graph::JobContext&) {});
    }
    auto out = g.importBuffer("readback", {kWords * 4}, rhi::external(readback_), kHostRead, kHostRead);
    auto copy = g.addNode("Copy out", graph::NodeType::Transfer);
    copy.read(words, graph::Access::TransferSrc);
    out = copy.write(out, graph::Access::TransferDst);
    copy.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyBuffer(ctx.buffer(words), ctx.buffer(out), kWords * 4);
    });
    return device_->compile(std::move(g), {.name = "empty nodes", .queues = queues, .separateQueues = true});
  }

  double nodeStartMs(const rhi::GraphTimings& t, const rhi::ExecutableGraph& graph, const std::string& name) {
    const auto& nodes = graph.declaration().nodes();
    for (uint32_t n = 0; n < nodes.size(); ++n) {
      if (nodes[n].name == name) return t.nodeStartMs[n];
    }
    ADD_FAILURE() << "no node " << name;
    return -2;
  }

  rhi::BufferId readback_;
};

TEST_P(EmptyNodes, DataArrivesSilentlyAndEmptyNodesHaveNoGpuTime) {
  auto graph = build(4, GetParam());
  for (int frame = 0; frame < 3; ++frame) {
    device_->wait(device_->execute(*graph));
    const auto w = words(readback_, kWords);
    EXPECT_TRUE(std::all_of(w.begin(), w.end(), [](uint32_t v) { return v == 7u; })) << "frame " << frame;
  }
  const auto timings = graph->takeTimings();
  ASSERT_FALSE(timings.empty());
  const auto& last = timings.back();
  EXPECT_GE(nodeStartMs(last, *graph, "Fill 7"), 0.0);
  EXPECT_GE(nodeStartMs(last, *graph, "Copy out"), 0.0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(nodeStartMs(last, *graph, "Empty " + std::to_string(i)), -1.0) << i;
}

TEST_P(EmptyNodes, AGraphOfOnlyEmptyNodesRunsRepeatedly) {
  graph::FrameGraph g;
  graph::BufferHandle words = g.createBuffer("words", {kWords * 4});
  for (uint32_t i = 0; i < 16; ++i) {
    auto node = g.addNode("Empty " + std::to_string(i), i % 3 == 0 ? graph::NodeType::Graphics
                                                         : i % 3 == 1 ? graph::NodeType::Compute
                                                                      : graph::NodeType::Transfer);
    const graph::Access access = i % 3 == 2 ? graph::Access::TransferDst
                                 : i == 0   ? graph::Access::StorageWrite
                                            : graph::Access::StorageReadWrite;
    words = node.write(words, access);
    node.sideEffect();
    node.setJob([](graph::JobContext&) {});
  }
  auto graph = device_->compile(std::move(g), {.name = "only empty", .queues = GetParam(), .separateQueues = true});
  for (int frame = 0; frame < 4; ++frame) device_->execute(*graph);
  device_->waitIdle();
  const auto timings = graph->takeTimings();
  ASSERT_EQ(timings.size(), 4u);
  for (const double start : timings.back().nodeStartMs) EXPECT_EQ(start, -1.0);
}

INSTANTIATE_TEST_SUITE_P(Queues, EmptyNodes, testing::Values(1u, 3u),
                         [](const testing::TestParamInfo<uint32_t>& param) {
                           return std::string("Q").append(std::to_string(param.param));
                         });

}  // namespace
}  // namespace fgb::test
