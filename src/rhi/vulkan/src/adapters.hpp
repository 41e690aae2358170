// Physical devices: description for `fgbench devices`, requirement checks and the --device rule.
#pragma once

#include "vk.hpp"

#include <fgb/rhi/device.hpp>

#include <string_view>
#include <vector>

namespace fgb::vulkan {

rhi::AdapterInfo describeAdapter(VkPhysicalDevice device, uint32_t index);

// Picks an adapter per the contract: "auto" (first discrete, then integrated GPU, else a CPU
// device), "lavapipe" (a CPU device), "gpu" (discrete, then integrated), or an INDEX. Unusable
// adapters (no Vulkan 1.3 features) are skipped by the names and rejected by index.
// Throws InputError for a malformed selector, DeviceError when nothing matches.
uint32_t selectAdapter(const std::vector<rhi::AdapterInfo>& adapters, std::string_view selector);

}  // namespace fgb::vulkan
