#include <dlfcn.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fgb/harness/run/device_probe.hpp>

namespace fgb::harness {
namespace {

// The few NVML entry points used, with their C signatures (nvml.h is not a build dependency).
using NvmlDevice = struct NvmlDeviceOpaque*;
using NvmlReturn = int;  // 0: NVML_SUCCESS
constexpr int kClockSm = 1, kClockMemory = 2, kTemperatureGpu = 0;

using InitFn = NvmlReturn (*)();
using CountFn = NvmlReturn (*)(unsigned*);
using HandleFn = NvmlReturn (*)(unsigned, NvmlDevice*);
using UuidFn = NvmlReturn (*)(NvmlDevice, char*, unsigned);
using ClockFn = NvmlReturn (*)(NvmlDevice, int, unsigned*);
using TemperatureFn = NvmlReturn (*)(NvmlDevice, int, unsigned*);
using PowerFn = NvmlReturn (*)(NvmlDevice, unsigned*);
using ReasonsFn = NvmlReturn (*)(NvmlDevice, unsigned long long*);

// "GPU-8f1c2a3b-..." -> "8f1c2a3b...": NVML's UUID as the 32 hex digits of Vulkan's deviceUUID.
std::string hexDigitsOf(std::string uuid) {
  if (uuid.rfind("GPU-", 0) == 0) uuid.erase(0, 4);
  uuid.erase(std::remove(uuid.begin(), uuid.end(), '-'), uuid.end());
  std::transform(uuid.begin(), uuid.end(), uuid.begin(), [](unsigned char c) { return std::tolower(c); });
  return uuid;
}

template <class Fn>
Fn symbol(void* library, const char* name) {
  return reinterpret_cast<Fn>(dlsym(library, name));
}

}  // namespace

struct DeviceProbe::Nvml {
  void* library = nullptr;
  NvmlDevice device = nullptr;
  ClockFn clock = nullptr;
  TemperatureFn temperature = nullptr;
  PowerFn power = nullptr;
  ReasonsFn reasons = nullptr;
  ~Nvml() {
    if (const auto shutdown = symbol<InitFn>(library, "nvmlShutdown")) shutdown();
    dlclose(library);
  }
};

DeviceProbe::DeviceProbe(const render::DeviceDescription& device) {
  const char* override = std::getenv("FGBENCH_NVML_LIBRARY");
  const std::string file = override != nullptr && *override != '\0' ? override : "libnvidia-ml.so.1";
  void* library = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    unavailable_ = "no " + file + " (NVML comes with NVIDIA's driver)";
    return;
  }
  auto nvml = std::make_unique<Nvml>();
  nvml->library = library;
  const auto init = symbol<InitFn>(library, "nvmlInit_v2");
  const auto count = symbol<CountFn>(library, "nvmlDeviceGetCount_v2");
  const auto handle = symbol<HandleFn>(library, "nvmlDeviceGetHandleByIndex_v2");
  const auto uuid = symbol<UuidFn>(library, "nvmlDeviceGetUUID");
  nvml->clock = symbol<ClockFn>(library, "nvmlDeviceGetClockInfo");
  nvml->temperature = symbol<TemperatureFn>(library, "nvmlDeviceGetTemperature");
  nvml->power = symbol<PowerFn>(library, "nvmlDeviceGetPowerUsage");
  nvml->reasons = symbol<ReasonsFn>(library, "nvmlDeviceGetCurrentClocksEventReasons");
  if (nvml->reasons == nullptr) nvml->reasons = symbol<ReasonsFn>(library, "nvmlDeviceGetCurrentClocksThrottleReasons");
  if (!init || !count || !handle || !uuid || !nvml->clock || !nvml->temperature || !nvml->power) {
    unavailable_ = file + " lacks an NVML entry point";
    return;
  }
  if (init() != 0) {
    unavailable_ = "nvmlInit_v2 failed";
    return;
  }
  unsigned devices = 0;
  if (count(&devices) != 0) devices = 0;
  for (unsigned i = 0; i < devices && nvml->device == nullptr; ++i) {
    NvmlDevice candidate = nullptr;
    char text[96] = {};
    if (handle(i, &candidate) != 0 || uuid(candidate, text, sizeof text) != 0) continue;
    if (hexDigitsOf(text) == device.uuid) nvml->device = candidate;
  }
  if (nvml->device == nullptr) {
    unavailable_ = "no NVML device has the Vulkan device's UUID " + device.uuid;
    return;
  }
  nvml_ = std::move(nvml);
}

DeviceProbe::~DeviceProbe() = default;

std::optional<DeviceSample> DeviceProbe::sample() const {
  if (!nvml_) return std::nullopt;
  unsigned sm = 0, memory = 0, temperature = 0, milliwatts = 0;
  if (nvml_->clock(nvml_->device, kClockSm, &sm) != 0 || nvml_->clock(nvml_->device, kClockMemory, &memory) != 0 ||
      nvml_->temperature(nvml_->device, kTemperatureGpu, &temperature) != 0) {
    return std::nullopt;
  }
  DeviceSample sample;
  sample.smClockMHz = sm;
  sample.memoryClockMHz = memory;
  sample.temperatureC = temperature;
  if (nvml_->power(nvml_->device, &milliwatts) == 0) sample.powerW = milliwatts / 1000.0;
  unsigned long long reasons = 0;
  if (nvml_->reasons != nullptr && nvml_->reasons(nvml_->device, &reasons) == 0) sample.throttleReasons = reasons;
  return sample;
}

}  // namespace fgb::harness
