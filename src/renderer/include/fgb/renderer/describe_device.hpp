// The harness's description of a device, from the RHI's record of the adapter (field for field):
// for `fgbench devices` and for the device a workload opened.
#pragma once

#include <fgb/renderer/workload.hpp>
#include <fgb/rhi/device.hpp>

namespace fgb::render {

inline DeviceDescription describeDevice(const rhi::AdapterInfo& adapter) {
  return {adapter.index,          adapter.name,          adapter.driver,
          adapter.type,           adapter.apiVersion,    adapter.timestampPeriodNs,
          adapter.hostTimestamps, adapter.queueFamilies, adapter.uuid};
}

}  // namespace fgb::render
