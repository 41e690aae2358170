// Kept command buffers (graph::NodeBuilder::recordingDependsOn): a node with a key is recorded once
// per frame in flight and then submitted again while its key is unchanged; a changed key records
// exactly that node again (per node, debug.node_buffers) or its block (the nodes of its submit, by
// default); a node without a key records every execution, and so does its block;
// debug.record_every_frame records everything. The results must not depend on which buffers were
// reused, and synchronization validation must stay silent (kept buffers carry their barriers).
#include <algorithm>
#include <tuple>

#include "gpu_support.hpp"

namespace fgb::test {
namespace {

constexpr uint32_t kWords = 64;
constexpr uint32_t kBytes = kWords * 4;
constexpr uint32_t kFillB = 5;
constexpr uint32_t kFillC = 9;
constexpr uint32_t kSlots = 2;  // frames in flight (DeviceOptions default)

class RecordingReuse : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    readback_ = readbackBuffer("readback", 3 * kBytes);
  }

  struct Layout {
    bool recordEveryFrame = false;
    bool nodeBuffers = true;
    bool keyC = false;
  };

  // "Fill A" (key: fillA_, the value it fills with), "Fill B" (a constant key), "Fill C" (no key
  // unless keyC) each fill a transient; "Copy out" (constant key) copies the three into the
  // readback buffer. One queue: the four nodes are one submit, so one block.
  std::unique_ptr<rhi::ExecutableGraph> build(Layout layout) {
    graph::FrameGraph g;
    const auto fill = [&](const char* name, graph::BufferHandle buffer, const uint32_t* value) {
      auto node = g.addNode(name, graph::NodeType::Transfer);
      buffer = node.write(buffer, graph::Access::TransferDst);
      node.setJob([buffer, value](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().fillBuffer(ctx.buffer(buffer), 0, kBytes, *value);
      });
      return std::pair{node, buffer};
    };
    auto [fillA, a] = fill("Fill A", g.createBuffer("a", {kBytes}), &fillA_);
    fillA.recordingDependsOn([this] { return uint64_t{fillA_}; });
    auto [fillB, b] = fill("Fill B", g.createBuffer("b", {kBytes}), &kFillB);
    fillB.recordingFixed();
    auto [fillC, c] = fill("Fill C", g.createBuffer("c", {kBytes}), &kFillC);
    if (layout.keyC) fillC.recordingFixed();

    auto out = g.importBuffer("readback", {3 * kBytes}, rhi::external(readback_), kHostRead, kHostRead);
    auto copy = g.addNode("Copy out", graph::NodeType::Transfer);
    for (const auto source : {a, b, c}) copy.read(source, graph::Access::TransferSrc);
    out = copy.write(out, graph::Access::TransferDst);
    copy.setJob([=](graph::JobContext& context) {
      auto& ctx = rhi::rhiContext(context);
      uint64_t offset = 0;
      for (const auto source : {a, b, c}) {
        const rhi::BufferCopy region{0, offset, kBytes};
        ctx.cmd().copyBuffer(ctx.buffer(source), ctx.buffer(out), std::span(&region, 1));
        offset += kBytes;
      }
    });
    copy.recordingFixed();
    return device_->compile(
        std::move(g),
        {.name = "reuse", .queues = 1, .recordEveryFrame = layout.recordEveryFrame, .nodeBuffers = layout.nodeBuffers});
  }

  // Executes once, waits, checks the three regions; returns {recorded, reused}.
  std::pair<uint32_t, uint32_t> frame(rhi::ExecutableGraph& graph) {
    device_->wait(device_->execute(graph));
    const auto w = words(readback_, 3 * kWords);
    const auto region = [&](uint32_t r, uint32_t value) {
      return std::all_of(w.begin() + r * kWords, w.begin() + (r + 1) * kWords, [&](uint32_t v) { return v == value; });
    };
    EXPECT_TRUE(region(0, fillA_)) << "A, execution " << graph.executions();
    EXPECT_TRUE(region(1, kFillB)) << "B, execution " << graph.executions();
    EXPECT_TRUE(region(2, kFillC)) << "C, execution " << graph.executions();
    const auto host = graph.lastHostTimes();
    return {host.nodesRecorded, host.nodesReused};
  }

  uint32_t fillA_ = 3;
  rhi::BufferId readback_;
};

using Counts = std::pair<uint32_t, uint32_t>;

TEST_F(RecordingReuse, KeyedNodesRecordOncePerSlotThenOnlyWhenTheirKeyChanges) {
  auto graph = build({.nodeBuffers = true});
  // First use of each frame-in-flight slot: everything records.
  for (uint32_t slot = 0; slot < kSlots; ++slot) EXPECT_EQ(frame(*graph), Counts(4, 0)) << "slot " << slot;
  // Then only "Fill C" (no key) records.
  for (int i = 0; i < 3; ++i) EXPECT_EQ(frame(*graph), Counts(1, 3)) << "steady frame " << i;
  // A's key changes: A records again, once in each slot, and the data follows.
  fillA_ = 11;
  for (uint32_t slot = 0; slot < kSlots; ++slot) EXPECT_EQ(frame(*graph), Counts(2, 2)) << "slot " << slot;
  EXPECT_EQ(frame(*graph), Counts(1, 3));
}

TEST_F(RecordingReuse, RecordEveryFrameRecordsEveryNode) {
  for (const bool nodeBuffers : {true, false}) {
    auto graph = build({.recordEveryFrame = true, .nodeBuffers = nodeBuffers});
    for (int i = 0; i < 5; ++i) EXPECT_EQ(frame(*graph), Counts(4, 0)) << "frame " << i << ", " << nodeBuffers;
    fillA_ = 12;
    EXPECT_EQ(frame(*graph), Counts(4, 0));
  }
}

TEST_F(RecordingReuse, BlockIsKeptWhileNoNodeInItChanged) {
  auto graph = build({.nodeBuffers = false, .keyC = true});
  for (uint32_t slot = 0; slot < kSlots; ++slot) EXPECT_EQ(frame(*graph), Counts(4, 0)) << "slot " << slot;
  for (int i = 0; i < 3; ++i) EXPECT_EQ(frame(*graph), Counts(0, 4)) << "steady frame " << i;
  // A's key changes: the whole block records again, once in each slot, and the data follows.
  fillA_ = 11;
  for (uint32_t slot = 0; slot < kSlots; ++slot) EXPECT_EQ(frame(*graph), Counts(4, 0)) << "slot " << slot;
  EXPECT_EQ(frame(*graph), Counts(0, 4));
}

TEST_F(RecordingReuse, BlockWithAnUnkeyedNodeRecordsEveryExecution) {
  auto graph = build({.nodeBuffers = false, .keyC = false});
  for (int i = 0; i < 4; ++i) EXPECT_EQ(frame(*graph), Counts(4, 0)) << "frame " << i;
}

// Reused nodes whose neighbours record nothing: the empty nodes' barriers move into the next
// node that records work (and the submit's last node), which a kept buffer must reproduce, on
// one queue and on three, per node and as blocks.
class RecordingReuseEmptyNodes : public GpuTest, public testing::WithParamInterface<std::tuple<uint32_t, bool>> {};

TEST_P(RecordingReuseEmptyNodes, KeptBuffersCarryTheBarriersOfEmptyNodes) {
  const auto readback = readbackBuffer("readback", kBytes);
  graph::FrameGraph g;
  graph::BufferHandle data = g.createBuffer("words", {kBytes});
  uint32_t value = 7;
  {
    auto node = g.addNode("Fill", graph::NodeType::Transfer);
    data = node.write(data, graph::Access::TransferDst);
    node.setJob([data, &value](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().fillBuffer(ctx.buffer(data), 0, kBytes, value);
    });
    node.recordingDependsOn([&value] { return uint64_t{value}; });
  }
  for (uint32_t i = 0; i < 4; ++i) {
    const bool compute = i % 2 == 0;
    auto node = g.addNode("Empty " + std::to_string(i), compute ? graph::NodeType::Compute : graph::NodeType::Transfer);
    data = node.write(data, compute ? graph::Access::StorageReadWrite : graph::Access::TransferDst);
    node.sideEffect();
    node.setJob([](graph::JobContext&) {});
    node.recordingFixed();
  }
  auto out = g.importBuffer("readback", {kBytes}, rhi::external(readback), kHostRead, kHostRead);
  auto copy = g.addNode("Copy out", graph::NodeType::Transfer);
  copy.read(data, graph::Access::TransferSrc);
  out = copy.write(out, graph::Access::TransferDst);
  copy.setJob([=](graph::JobContext& c) {
    auto& ctx = rhi::rhiContext(c);
    ctx.cmd().copyBuffer(ctx.buffer(data), ctx.buffer(out), kBytes);
  });
  copy.recordingFixed();
  const auto [queues, nodeBuffers] = GetParam();
  auto graph = device_->compile(
      std::move(g), {.name = "reuse empty", .queues = queues, .separateQueues = true, .nodeBuffers = nodeBuffers});
  for (int frame = 0; frame < 8; ++frame) {
    if (frame == 5) value = 8;  // Fill records again; the others stay kept
    device_->wait(device_->execute(*graph));
    const auto w = words(readback, kWords);
    EXPECT_TRUE(std::all_of(w.begin(), w.end(), [&](uint32_t v) { return v == value; })) << "frame " << frame;
    if (frame >= static_cast<int>(kSlots) && frame != 5 && frame != 6) {
      EXPECT_EQ(graph->lastHostTimes().nodesRecorded, 0u) << "frame " << frame;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Queues, RecordingReuseEmptyNodes, testing::Combine(testing::Values(1u, 3u), testing::Bool()),
                         [](const testing::TestParamInfo<std::tuple<uint32_t, bool>>& param) {
                           return std::string("Q")
                               .append(std::to_string(std::get<0>(param.param)))
                               .append(std::get<1>(param.param) ? "_nodes" : "_blocks");
                         });

}  // namespace
}  // namespace fgb::test
