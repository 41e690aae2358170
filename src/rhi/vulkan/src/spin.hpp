// debug.slow_pass (rhi::GraphOptions::slowNode): a compute dispatch recorded at the end of one
// node, inside the node's timestamps, that costs a chosen fraction of the node's own GPU time, so
// that timing tests have a real slowdown of known size to find. It writes only a scratch buffer of
// its own through a descriptor set of its own: no frame-graph resource, so the image is unchanged.
//
// Calibration: the executor writes a third timestamp where the node's own work ends (before the
// spin), so each execution tells the node's own time and the spin's. Executions 1..kCalibration
// (the first is skipped: pipeline and memory first-touch) set the iteration count from the
// medians of both; after that it is fixed, so the measured frames (after the harness' warm-up of
// 8 by default) all carry the same spin.
#pragma once

#include "device.hpp"

#include <cstdint>
#include <vector>

namespace fgb::vulkan {

class SpinWork {
 public:
  static constexpr uint64_t kCalibration = 4;

  SpinWork(VulkanDevice& device, double fraction);
  SpinWork(const SpinWork&) = delete;
  SpinWork& operator=(const SpinWork&) = delete;

  // An execution barrier after everything recorded before (the spin adds to the node's time instead
  // of overlapping its work), then the spin dispatch. Binds a pipeline layout of its own at the
  // compute bind point: the caller must rebind its own descriptor set afterwards.
  void record(VkCommandBuffer cmd) const;
  [[nodiscard]] uint32_t iterations() const { return iterations_; }
  // One execution's node time without the spin and the spin's time, with the iterations it ran.
  void observe(uint64_t execution, double ownMs, double spinMs, uint32_t iterations);

 private:
  VulkanDevice& device_;
  double fraction_;
  uint32_t iterations_ = 1u << 12;
  Owned<VkDeviceMemory> memory_;  // (declared first: destroyed after the buffer bound to it)
  Owned<VkBuffer> scratch_;
  Owned<VkDescriptorSetLayout> setLayout_;
  Owned<VkDescriptorPool> pool_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Owned<VkPipelineLayout> layout_;
  Owned<VkPipeline> pipeline_;
  std::vector<double> ownMs_, msPerIteration_;  // calibration samples
};

}  // namespace fgb::vulkan
