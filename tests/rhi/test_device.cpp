// Device creation, selection errors, resources and pipelines under validation.
#include "gpu_support.hpp"

#include <fgb/core/error.hpp>
#include <fgb/renderer/workload.hpp>
#include <fgb/rhi/upload.hpp>
#include <fgb/vulkan/backend.hpp>

#include <cstring>
#include <numeric>

namespace fgb::test {
namespace {

TEST(Device, CreatesWithValidationAndDescribesItself) {
  auto device = makeValidatedDevice();
  const auto& adapter = device->adapter();
  EXPECT_FALSE(adapter.name.empty());
  EXPECT_FALSE(adapter.queueFamilies.empty());
  EXPECT_GT(adapter.timestampPeriodNs, 0.0);
  EXPECT_GE(device->maxSamples(), 1u);
  EXPECT_TRUE(device->sampleCounts() & 1u);
  EXPECT_TRUE(device->sampleCounts() & device->maxSamples());
  EXPECT_EQ(device->sampleCounts() & ~0xfu, 0u);
  if (adapter.type == "cpu") {
    EXPECT_TRUE(adapter.hostTimestamps);
  }
  EXPECT_EQ(device->validationMessages(), 0u);
}

TEST(Device, ListedDevicesMatchTheSelectedOne) {
  const auto devices = render::listDevices();
  ASSERT_FALSE(devices.empty());
  auto device = makeValidatedDevice();
  ASSERT_LT(device->adapter().index, devices.size());
  EXPECT_EQ(devices[device->adapter().index].name, device->adapter().name);
}

TEST(Device, MissingIndexThrowsDeviceErrorWithAClearMessage) {
  try {
    vulkan::createDevice({.selector = "99"});
    FAIL() << "device 99 should not exist";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("--device 99"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("device(s)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(vulkan::createDevice({.selector = "fastest"}), InputError);
}

class Resources : public GpuTest {};

TEST_F(Resources, CreatesBuffersTexturesSamplersPipelinesCleanly) {
  const auto buffer = device_->createBuffer({"storage", 4096, rhi::kBufferStorage, rhi::MemoryUsage::DeviceLocal});
  const auto texture = device_->createTexture({"colour", graph::Format::R16G16B16A16Sfloat, {64, 64, 1}, 1, 1, 1,
                                               rhi::kTextureSampled | rhi::kTextureColorAttachment});
  const auto depth = device_->createTexture({"depth", graph::Format::D32Sfloat, {64, 64, 1}, 1, 1, device_->maxSamples(),
                                             rhi::kTextureDepthAttachment});
  const auto sampler = device_->createSampler({"linear"});
  EXPECT_NE(device_->storageBufferIndex(buffer), rhi::kInvalidId);
  EXPECT_NE(device_->sampledTextureIndex(texture), rhi::kInvalidId);
  EXPECT_EQ(device_->sampledTextureIndex(depth), rhi::kInvalidId);  // not sampled
  EXPECT_NE(device_->samplerIndex(sampler), rhi::kInvalidId);
  EXPECT_TRUE(device_->mapped(buffer).empty());  // device-local
  device_->createComputePipeline({"fill", "common/fill.comp"});
  device_->createGraphicsPipeline({.name = "solid", .vertexShader = "common/fullscreen.vert",
                                   .fragmentShader = "common/solid.frag",
                                   .colorFormats = {graph::Format::R8G8B8A8Unorm}});
  EXPECT_THROW(device_->createComputePipeline({"missing", "nope/missing.comp"}), InputError);
}

TEST_F(Resources, UploadIsATransferNodeAndArrives) {
  std::vector<uint32_t> values(1000);
  std::iota(values.begin(), values.end(), 7u);
  const uint64_t bytes = values.size() * 4;
  const auto target = device_->createBuffer({"target", bytes, rhi::kBufferTransferDst | rhi::kBufferTransferSrc,
                                             rhi::MemoryUsage::DeviceLocal});
  rhi::uploadBuffer(*device_, target, std::as_bytes(std::span(values)));

  // Read it back through another transfer graph.
  const auto readback = readbackBuffer("readback", bytes);
  graph::FrameGraph g;
  const graph::ImportState any{graph::kStageAllCommands, graph::kAccessTransferRead, graph::Layout::Undefined};
  const auto src = g.importBuffer("target", {bytes}, rhi::external(target), any, any);
  auto dst = g.importBuffer("readback", {bytes}, rhi::external(readback), kHostRead, kHostRead);
  auto node = g.addNode("Copy back", graph::NodeType::Transfer);
  node.read(src, graph::Access::TransferSrc);
  dst = node.write(dst, graph::Access::TransferDst);
  node.setJob([=](graph::JobContext& c) { rhi::rhiContext(c).cmd().copyBuffer(rhi::rhiContext(c).buffer(src),
                                                                               rhi::rhiContext(c).buffer(dst), bytes); });
  auto executable = device_->compile(std::move(g), {.name = "copy back"});
  device_->wait(device_->execute(*executable));
  EXPECT_EQ(words(readback, values.size()), values);
}

}  // namespace
}  // namespace fgb::test
