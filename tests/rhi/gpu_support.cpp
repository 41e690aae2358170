#include "gpu_support.hpp"

#include <fgb/vulkan/backend.hpp>

#include <cstdlib>
#include <cstring>

namespace fgb::test {

std::string testDeviceSelector() {
  const char* selector = std::getenv("FGBENCH_TEST_DEVICE");
  return selector != nullptr && selector[0] != '\0' ? selector : "auto";
}

std::unique_ptr<rhi::Device> makeValidatedDevice(rhi::DeviceOptions options) {
  options.selector = testDeviceSelector();
  options.validation = true;
  return vulkan::createDevice(options);
}

void GpuTest::SetUp() { device_ = makeValidatedDevice(deviceOptions()); }

void GpuTest::TearDown() {
  if (!device_) return;
  device_->waitIdle();
  if (!expectMessages_) {
    EXPECT_EQ(device_->validationMessages(), 0u) << "validation reported problems (see stderr)";
  }
}

rhi::BufferId GpuTest::readbackBuffer(const std::string& name, uint64_t size) {
  return device_->createBuffer({name, size, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
}

std::vector<uint32_t> GpuTest::words(rhi::BufferId buffer, size_t count) {
  const auto bytes = device_->mapped(buffer);
  std::vector<uint32_t> result(count);
  std::memcpy(result.data(), bytes.data(), count * sizeof(uint32_t));
  return result;
}

}  // namespace fgb::test
