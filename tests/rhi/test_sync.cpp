// Same-layout hazards must still be synchronised: write-after-write and read-after-write on one
// storage buffer (GENERAL-like, no layout) and on one colour attachment (layout unchanged between
// two render passes). Synchronization validation proves the barriers are right — and, with those
// barriers dropped on purpose (test-only option), that it would notice if they were missing.
#include "gpu_support.hpp"

#include <array>
#include <cstring>

namespace fgb::test {
namespace {

constexpr uint32_t kWords = 256;
constexpr uint32_t kSize = 16;

struct FillPush {
  uint32_t buffer, count, value, mode;
};
struct ColorPush {
  std::array<float, 4> color;
};

// Parameter: descriptor fallback (no update-after-bind), where synchronization validation can see
// which storage buffers a dispatch accesses; with bindless descriptors it cannot.
class SameLayout : public GpuTest, public testing::WithParamInterface<bool> {
 protected:
  rhi::DeviceOptions deviceOptions() const override { return {.forceDescriptorFallback = GetParam()}; }

  void SetUp() override {
    GpuTest::SetUp();
    fill_ = device_->createComputePipeline({"fill", "common/fill.comp"});
    rhi::GraphicsPipelineDesc solid{.name = "solid additive", .vertexShader = "common/fullscreen.vert",
                                    .fragmentShader = "common/solid.frag"};
    solid.colorFormats = {graph::Format::R8G8B8A8Unorm};
    solid.blend = {rhi::BlendMode::Additive};
    solid_ = device_->createGraphicsPipeline(solid);
    words_ = readbackBuffer("words readback", kWords * 4);
    pixels_ = readbackBuffer("pixels readback", kSize * kSize * 4);
    transfer_ = readbackBuffer("transfer readback", kWords * 4 + kSize * kSize * 4);
  }

  std::unique_ptr<rhi::ExecutableGraph> build(bool dropSameLayoutBarriers) {
    graph::FrameGraph g;
    addBufferChain(g);
    addAttachmentChain(g);
    addTransferChain(g);
    return device_->compile(std::move(g), {.name = "same layout", .testDropSameLayoutBarriers = dropSameLayoutBarriers});
  }

  void addBufferChain(graph::FrameGraph& g) {
    graph::BufferHandle words = g.createBuffer("words", {kWords * 4});
    const auto pass = [&](const char* name, graph::Access access, uint32_t value, uint32_t mode) {
      auto node = g.addNode(name, graph::NodeType::Compute);
      words = node.write(words, access);
      node.setJob([=, fill = fill_, handle = words](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().bindPipeline(fill);
        ctx.cmd().push(FillPush{ctx.storageBufferIndex(handle), kWords, value, mode});
        ctx.cmd().dispatch(kWords / 64);
      });
    };
    pass("Fill (write)", graph::Access::StorageWrite, 100, 0);
    pass("Add 5 (RAW + WAW)", graph::Access::StorageReadWrite, 5, 1);
    pass("Add 7 (RAW + WAW)", graph::Access::StorageReadWrite, 7, 1);
    auto readback = g.importBuffer("words readback", {kWords * 4}, rhi::external(words_), kHostRead, kHostRead);
    auto node = g.addNode("Copy words", graph::NodeType::Transfer);
    node.read(words, graph::Access::TransferSrc);
    readback = node.write(readback, graph::Access::TransferDst);
    node.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyBuffer(ctx.buffer(words), ctx.buffer(readback), kWords * 4);
    });
  }

  void addAttachmentChain(graph::FrameGraph& g) {
    graph::TextureHandle target = g.createTexture("target", {graph::Format::R8G8B8A8Unorm, {kSize, kSize, 1}});
    const auto draw = [&](const char* name, graph::LoadOp load, std::array<float, 4> color) {
      auto node = g.addNode(name, graph::NodeType::Graphics);
      target = node.addColorTarget(target, load, graph::ClearValue{{0, 0, 0, 0}});
      node.setJob([=, solid = solid_](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().bindPipeline(solid);
        ctx.cmd().push(ColorPush{color});
        ctx.cmd().draw(3);
      });
    };
    draw("Draw red (clear)", graph::LoadOp::Clear, {0.25f, 0, 0, 0.5f});
    draw("Add green (load: RAW + WAW, same layout)", graph::LoadOp::Load, {0, 0.5f, 0, 0.5f});
    auto readback = g.importBuffer("pixels readback", {kSize * kSize * 4}, rhi::external(pixels_), kHostRead, kHostRead);
    auto node = g.addNode("Copy pixels", graph::NodeType::Transfer);
    node.read(target, graph::Access::TransferSrc);
    readback = node.write(readback, graph::Access::TransferDst);
    node.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyTextureToBuffer(ctx.texture(target), ctx.buffer(readback));
    });
  }

  // Transfer writes and reads, which the synchronization validation of every layer version tracks
  // (accesses through bindless descriptors and dynamic-rendering attachments are invisible to the
  // 1.3.239 layer): fill, fill half again (WAW), copy out (RAW); clear an image twice (WAW, the
  // layout stays TRANSFER_DST).
  void addTransferChain(graph::FrameGraph& g) {
    graph::BufferHandle words = g.createBuffer("transfer words", {kWords * 4});
    graph::TextureHandle image = g.createTexture("cleared twice", {graph::Format::R8G8B8A8Unorm, {kSize, kSize, 1}});
    {
      // TransferDst discards the previous contents, so without sideEffect() this node would be
      // culled as overwritten; keeping it makes the second fill a real write-after-write.
      // Compute, not transfer: vkCmdClearColorImage needs a graphics or compute queue.
      auto node = g.addNode("Fill 3", graph::NodeType::Compute);
      node.sideEffect();
      words = node.write(words, graph::Access::TransferDst);
      image = node.write(image, graph::Access::TransferDst);
      node.setJob([=](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().fillBuffer(ctx.buffer(words), 0, kWords * 4, 3);
        ctx.cmd().clearTexture(ctx.texture(image), {1, 0, 0, 1});
      });
    }
    {
      auto node = g.addNode("Fill 9 over the first half (WAW)", graph::NodeType::Compute);
      words = node.write(words, graph::Access::TransferDst);
      image = node.write(image, graph::Access::TransferDst);
      node.setJob([=](graph::JobContext& c) {
        auto& ctx = rhi::rhiContext(c);
        ctx.cmd().fillBuffer(ctx.buffer(words), 0, kWords * 2, 9);
        ctx.cmd().clearTexture(ctx.texture(image), {0, 0, 1, 1});
      });
    }
    auto readback = g.importBuffer("transfer readback", {kWords * 4 + kSize * kSize * 4}, rhi::external(transfer_),
                                   kHostRead, kHostRead);
    // On the fills' queue: the RAW must be a same-queue hazard (across queues a semaphore orders it).
    auto node = g.addNode("Copy transfer results (RAW)", graph::NodeType::Transfer, graph::QueueClass::Compute);
    node.read(words, graph::Access::TransferSrc);
    node.read(image, graph::Access::TransferSrc);
    readback = node.write(readback, graph::Access::TransferDst);
    node.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyBuffer(ctx.buffer(words), ctx.buffer(readback), kWords * 4);
      ctx.cmd().copyTextureToBuffer(ctx.texture(image), ctx.buffer(readback), kWords * 4);
    });
  }

  rhi::PipelineId fill_, solid_;
  rhi::BufferId words_, pixels_, transfer_;
};

TEST_P(SameLayout, RawAndWawAreSynchronisedAndGiveTheRightResult) {
  auto graph = build(false);
  for (int frame = 0; frame < 3; ++frame) device_->execute(*graph);
  device_->waitIdle();
  const auto values = words(words_, kWords);
  for (uint32_t i = 0; i < kWords; ++i) ASSERT_EQ(values[i], 100 + i + 12) << "word " << i;
  const auto bytes = device_->mapped(pixels_);
  const auto at = [&](size_t i) { return std::to_integer<int>(bytes[i]); };
  for (size_t p = 0; p < kSize * kSize; ++p) {
    ASSERT_NEAR(at(p * 4 + 0), 64, 1) << "pixel " << p;
    ASSERT_NEAR(at(p * 4 + 1), 128, 1) << "pixel " << p;
    ASSERT_EQ(at(p * 4 + 2), 0) << "pixel " << p;
    ASSERT_NEAR(at(p * 4 + 3), 255, 1) << "pixel " << p;  // blended: GPUs round 254 or 255
  }
  const auto transferWords = words(transfer_, kWords);
  for (uint32_t i = 0; i < kWords; ++i) ASSERT_EQ(transferWords[i], i < kWords / 2 ? 9u : 3u) << "word " << i;
  const auto transferBytes = device_->mapped(transfer_).subspan(kWords * 4);
  for (size_t p = 0; p < kSize * kSize; ++p) {
    ASSERT_EQ(std::to_integer<int>(transferBytes[p * 4 + 0]), 0) << "cleared pixel " << p;
    ASSERT_EQ(std::to_integer<int>(transferBytes[p * 4 + 2]), 255) << "cleared pixel " << p;
  }
}

TEST_P(SameLayout, DroppingSameLayoutBarriersIsCaughtBySynchronizationValidation) {
  expectValidationMessages();
  auto graph = build(true);
  device_->wait(device_->execute(*graph));
  device_->waitIdle();
  EXPECT_GT(device_->validationMessages(), 0u) << "sync validation did not notice missing barriers: is it live?";
  bool readAfterWrite = false;
  bool writeAfterWrite = false;
  for (const auto& message : device_->validationLog()) {
    // Record-time messages are named SYNC-HAZARD-...; newer layers' submit-time ones (hazards
    // between the per-step command buffers of one submit) say "..._AFTER_... hazard detected".
    readAfterWrite |= message.find("SYNC-HAZARD-READ-AFTER-WRITE") != std::string::npos ||
                      message.find("READ_AFTER_WRITE hazard") != std::string::npos;
    writeAfterWrite |= message.find("SYNC-HAZARD-WRITE-AFTER-WRITE") != std::string::npos ||
                       message.find("WRITE_AFTER_WRITE hazard") != std::string::npos;
  }
  EXPECT_TRUE(readAfterWrite) << "expected a read-after-write hazard";
  EXPECT_TRUE(writeAfterWrite) << "expected a write-after-write hazard";
}

INSTANTIATE_TEST_SUITE_P(Descriptors, SameLayout, testing::Values(false, true),
                         [](const auto& param) { return param.param ? "Fallback" : "Bindless"; });

}  // namespace
}  // namespace fgb::test
