// Shared fixture of the GPU tests: a validated device (validation + synchronization validation),
// and a check after every test that the layers reported nothing.
#pragma once

#include <fgb/rhi/device.hpp>
#include <fgb/rhi/job_context.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fgb::test {

// FGBENCH_TEST_DEVICE selects the device (default "auto").
std::string testDeviceSelector();
std::unique_ptr<rhi::Device> makeValidatedDevice(rhi::DeviceOptions options = {});

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  // Call when a test is meant to trigger validation messages.
  void expectValidationMessages() { expectMessages_ = true; }
  virtual rhi::DeviceOptions deviceOptions() const { return {}; }

  rhi::BufferId readbackBuffer(const std::string& name, uint64_t size);
  std::vector<uint32_t> words(rhi::BufferId buffer, size_t count);

  std::unique_ptr<rhi::Device> device_;
  bool expectMessages_ = false;
};

// Import states for buffers the host reads after the graph.
inline constexpr graph::ImportState kHostRead{graph::kStageHost, graph::kAccessHostRead, graph::Layout::Undefined};

}  // namespace fgb::test
