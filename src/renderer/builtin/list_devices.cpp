// listDevices(): the Vulkan adapters as the harness describes devices.
#include <fgb/renderer/workload.hpp>
#include <fgb/vulkan/backend.hpp>

#include "proof_workload.hpp"

namespace fgb::render {

DeviceDescription describeDevice(const rhi::AdapterInfo& adapter) {
  DeviceDescription d;
  d.index = adapter.index;
  d.name = adapter.name;
  d.driver = adapter.driver;
  d.type = adapter.type;
  d.apiVersion = adapter.apiVersion;
  d.timestampPeriodNs = adapter.timestampPeriodNs;
  d.hostTimestamps = adapter.hostTimestamps;
  d.queueFamilies = adapter.queueFamilies;
  return d;
}

std::vector<DeviceDescription> listDevices() {
  std::vector<DeviceDescription> devices;
  for (const auto& adapter : vulkan::enumerateAdapters()) devices.push_back(describeDevice(adapter));
  return devices;
}

}  // namespace fgb::render
