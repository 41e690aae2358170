// listDevices(): the Vulkan adapters as the harness describes devices.
#include <fgb/renderer/describe_device.hpp>
#include <fgb/vulkan/backend.hpp>

namespace fgb::render {

std::vector<DeviceDescription> listDevices() {
  std::vector<DeviceDescription> devices;
  for (const auto& adapter : vulkan::enumerateAdapters()) devices.push_back(describeDevice(adapter));
  return devices;
}

}  // namespace fgb::render
