// Samples a device's clocks, temperature and power where its driver exposes them: NVIDIA's NVML,
// loaded with dlopen at run time (nothing is linked; without the library the probe says why and
// samples nothing). The NVML device is the one whose UUID is the Vulkan device's.
// $FGBENCH_NVML_LIBRARY names another library file (tests load a fake one).
#pragma once

#include <fgb/harness/results/clock_check.hpp>
#include <fgb/renderer/workload.hpp>
#include <memory>
#include <optional>
#include <string>

namespace fgb::harness {

class DeviceProbe {
 public:
  explicit DeviceProbe(const render::DeviceDescription& device);
  ~DeviceProbe();
  DeviceProbe(const DeviceProbe&) = delete;
  DeviceProbe& operator=(const DeviceProbe&) = delete;

  [[nodiscard]] bool available() const { return nvml_ != nullptr; }
  [[nodiscard]] const std::string& unavailable() const { return unavailable_; }
  // Empty when unavailable or when the driver refuses the query.
  [[nodiscard]] std::optional<DeviceSample> sample() const;

 private:
  struct Nvml;
  std::unique_ptr<Nvml> nvml_;
  std::string unavailable_;
};

}  // namespace fgb::harness
