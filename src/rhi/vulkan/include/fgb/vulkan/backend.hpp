// The Vulkan backend of the RHI (through volk; Vulkan 1.3: dynamic rendering, synchronization2,
// timeline semaphores). Headless: no surface, no swapchain. No Vulkan types in this header.
#pragma once

#include <fgb/rhi/device.hpp>

#include <memory>
#include <vector>

namespace fgb::vulkan {

// Every physical device, in enumeration order (the INDEX of --device). Throws fgb::DeviceError
// when the Vulkan loader or instance is unusable.
std::vector<rhi::AdapterInfo> enumerateAdapters();

// Creates the device chosen by options.selector: "auto" (first discrete, then integrated GPU,
// else a CPU implementation such as lavapipe), "lavapipe", "gpu" or an index.
// Throws fgb::InputError for a malformed selector, fgb::DeviceError when no device matches or
// creation fails. FGBENCH_VALIDATION=1 in the environment turns validation on too.
std::unique_ptr<rhi::Device> createDevice(const rhi::DeviceOptions& options);

}  // namespace fgb::vulkan
