// Several graphs per frame: sequential runs are chained on timeline values (a later graph sees the
// earlier one's writes), async runs are independent and report completion by polling or callback.
#include "gpu_support.hpp"

#include <cstring>

namespace fgb::test {
namespace {

constexpr uint32_t kWords = 128;

struct FillPush {
  uint32_t buffer, count, value, mode;
};

class MultiGraph : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    fill_ = device_->createComputePipeline({"fill", "common/fill.comp"});
  }

  // One compute node on an imported storage buffer: mode 0 writes value + i, mode 1 adds value.
  // With `readback`, a transfer node copies the result out.
  std::unique_ptr<rhi::ExecutableGraph> computeGraph(const std::string& name, rhi::BufferId target, uint32_t value,
                                                     uint32_t mode, rhi::BufferId readback = {}) {
    graph::FrameGraph g;
    const graph::ImportState shared{graph::kStageAllCommands, graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite |
                                                                  graph::kAccessTransferRead,
                                    graph::Layout::Undefined};
    auto words = g.importBuffer("words", {kWords * 4}, rhi::external(target), shared, shared);
    auto node = g.addNode(name, graph::NodeType::Compute);
    words = node.write(words, mode == 0 ? graph::Access::StorageWrite : graph::Access::StorageReadWrite);
    node.setJob([=, fill = fill_](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().bindPipeline(fill);
      ctx.cmd().push(FillPush{ctx.storageBufferIndex(words), kWords, value, mode});
      ctx.cmd().dispatch(kWords / 64);
    });
    if (readback.valid()) {
      auto out = g.importBuffer("readback", {kWords * 4}, rhi::external(readback), kHostRead, kHostRead);
      auto copy = g.addNode(name + " readback", graph::NodeType::Transfer);
      copy.read(words, graph::Access::TransferSrc);
      out = copy.write(out, graph::Access::TransferDst);
      copy.setJob([=](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().copyBuffer(ctx.buffer(words), ctx.buffer(out), kWords * 4);
      });
    }
    return device_->compile(std::move(g), {.name = name});
  }

  rhi::BufferId storage(const char* name) {
    return device_->createBuffer({name, kWords * 4, rhi::kBufferStorage | rhi::kBufferTransferSrc, rhi::MemoryUsage::DeviceLocal});
  }

  rhi::PipelineId fill_;
};

TEST_F(MultiGraph, SequentialGraphsSeeEachOthersWrites) {
  const auto shared = storage("shared");
  const auto readback = readbackBuffer("sequential readback", kWords * 4);
  auto writer = computeGraph("write", shared, 1000, 0);
  auto adder = computeGraph("add", shared, 10, 1, readback);
  for (uint32_t frame = 0; frame < 4; ++frame) {
    device_->execute(*writer, rhi::RunMode::Sequential);
    device_->execute(*adder, rhi::RunMode::Sequential);
  }
  device_->waitIdle();
  const auto values = words(readback, kWords);
  for (uint32_t i = 0; i < kWords; ++i) ASSERT_EQ(values[i], 1000 + i + 10) << "word " << i;
}

TEST_F(MultiGraph, AsyncGraphCompletesByPollingAndCallback) {
  const auto own = storage("async");
  const auto readback = readbackBuffer("async readback", kWords * 4);
  auto background = computeGraph("async fill", own, 7, 0, readback);
  auto foreground = computeGraph("foreground", storage("foreground"), 1, 0);

  bool called = false;
  const rhi::RunTicket ticket = device_->execute(*background, rhi::RunMode::Async, [&] { called = true; });
  device_->execute(*foreground, rhi::RunMode::Sequential);
  while (!device_->isComplete(ticket)) device_->poll();
  device_->poll();
  EXPECT_TRUE(called);
  const auto values = words(readback, kWords);
  for (uint32_t i = 0; i < kWords; ++i) ASSERT_EQ(values[i], 7 + i) << "word " << i;

  // A ticket of a later execution is not complete before it was submitted, and is after a wait.
  const rhi::RunTicket second = device_->execute(*background, rhi::RunMode::Async);
  device_->wait(second);
  EXPECT_TRUE(device_->isComplete(second));
  EXPECT_EQ(background->executions(), 2u);
}

TEST_F(MultiGraph, TimingsComeBackOncePerExecutionInOrder) {
  auto graph = computeGraph("timed", storage("timed"), 3, 0);
  for (int i = 0; i < 5; ++i) device_->execute(*graph);
  device_->waitIdle();
  const auto timings = graph->takeTimings();
  ASSERT_EQ(timings.size(), 5u);
  for (uint64_t i = 0; i < timings.size(); ++i) {
    EXPECT_EQ(timings[i].execution, i);
    ASSERT_EQ(timings[i].nodeMs.size(), 1u);
    EXPECT_GE(timings[i].nodeMs[0], 0.0);
    EXPECT_GE(timings[i].gpuMs, timings[i].nodeMs[0] - 1e-9);
  }
  EXPECT_TRUE(graph->takeTimings().empty());
}

TEST(DescriptorFallback, RendersWithoutBindlessToo) {
  auto device = makeValidatedDevice({.forceDescriptorFallback = true});
  EXPECT_FALSE(device->bindless());
  const auto fill = device->createComputePipeline({"fill", "common/fill.comp"});
  const auto readback = device->createBuffer({"readback", kWords * 4, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  graph::FrameGraph g;
  auto words = g.createBuffer("transient words", {kWords * 4});
  auto out = g.importBuffer("readback", {kWords * 4}, rhi::external(readback), kHostRead, kHostRead);
  auto node = g.addNode("Fill", graph::NodeType::Compute);
  words = node.write(words, graph::Access::StorageWrite);
  node.setJob([=](graph::JobContext& c) {
    auto& ctx = rhi::rhiContext(c);
    ctx.cmd().bindPipeline(fill);
    ctx.cmd().push(FillPush{ctx.storageBufferIndex(words), kWords, 42, 0});
    ctx.cmd().dispatch(kWords / 64);
  });
  auto copy = g.addNode("Copy", graph::NodeType::Transfer);
  copy.read(words, graph::Access::TransferSrc);
  out = copy.write(out, graph::Access::TransferDst);
  copy.setJob([=](graph::JobContext& c) {
    auto& ctx = rhi::rhiContext(c);
    ctx.cmd().copyBuffer(ctx.buffer(words), ctx.buffer(out), kWords * 4);
  });
  auto graph = device->compile(std::move(g), {.name = "fallback"});
  device->wait(device->execute(*graph));
  device->waitIdle();
  const auto bytes = device->mapped(readback);
  std::vector<uint32_t> values(kWords);
  std::memcpy(values.data(), bytes.data(), kWords * 4);
  for (uint32_t i = 0; i < kWords; ++i) ASSERT_EQ(values[i], 42 + i);
  EXPECT_EQ(device->validationMessages(), 0u);
}

}  // namespace
}  // namespace fgb::test
