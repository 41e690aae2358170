#include "adapters.hpp"

#include <fgb/core/error.hpp>

#include <charconv>
#include <string>

namespace fgb::vulkan {
namespace {

std::string typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    default: return "other";
  }
}

std::string versionString(uint32_t version) {
  return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
         std::to_string(VK_API_VERSION_PATCH(version));
}

std::string queueFlagsString(VkQueueFlags flags) {
  std::string text;
  const auto add = [&](VkQueueFlags bit, const char* name) {
    if ((flags & bit) == 0) return;
    if (!text.empty()) text += '|';
    text += name;
  };
  add(VK_QUEUE_GRAPHICS_BIT, "graphics");
  add(VK_QUEUE_COMPUTE_BIT, "compute");
  add(VK_QUEUE_TRANSFER_BIT, "transfer");
  add(VK_QUEUE_SPARSE_BINDING_BIT, "sparse");
  add(VK_QUEUE_VIDEO_DECODE_BIT_KHR, "video-decode");
  return text.empty() ? "none" : text;
}

// Why the backend cannot use this device, or "" when it can.
std::string missingRequirement(VkPhysicalDevice device, uint32_t apiVersion) {
  if (apiVersion < VK_API_VERSION_1_3) return "Vulkan " + versionString(apiVersion) + " < 1.3";
  auto v13 = vkStruct<VkPhysicalDeviceVulkan13Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES);
  auto v12 = vkStruct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
  v12.pNext = &v13;
  auto features = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  features.pNext = &v12;
  vkGetPhysicalDeviceFeatures2(device, &features);
  if (!v13.dynamicRendering) return "no dynamicRendering";
  if (!v13.synchronization2) return "no synchronization2";
  if (!v12.timelineSemaphore) return "no timelineSemaphore";
  if (!v12.hostQueryReset) return "no hostQueryReset";
  return {};
}

}  // namespace

rhi::AdapterInfo describeAdapter(VkPhysicalDevice device, uint32_t index) {
  auto driver = vkStruct<VkPhysicalDeviceDriverProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES);
  auto ids = vkStruct<VkPhysicalDeviceIDProperties>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES);
  driver.pNext = &ids;
  auto properties = vkStruct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2);
  properties.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &properties);
  const auto& p = properties.properties;

  rhi::AdapterInfo info;
  info.index = index;
  info.name = p.deviceName;
  info.driver = std::string(driver.driverName) + " (" + driver.driverInfo + ")";
  info.type = typeName(p.deviceType);
  info.apiVersion = versionString(p.apiVersion);
  info.timestampPeriodNs = p.limits.timestampPeriod;
  info.maxImageDimension2D = p.limits.maxImageDimension2D;
  // CPU implementations (lavapipe) read the host clock for "GPU" timestamps.
  info.hostTimestamps = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  info.uuid = hexUuid(ids.deviceUUID);  // finds this device in the driver's tools (NVML on NVIDIA)

  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &familyCount, families.data());
  info.timestampValidBits = 0;
  for (uint32_t i = 0; i < familyCount; ++i) {
    info.queueFamilies.push_back(std::to_string(i) + ": " + queueFlagsString(families[i].queueFlags) + " x" +
                                 std::to_string(families[i].queueCount));
    if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) info.timestampValidBits = families[i].timestampValidBits;
  }
  info.unusableReason = missingRequirement(device, p.apiVersion);
  info.usable = info.unusableReason.empty();
  return info;
}

namespace {

std::string adapterList(const std::vector<rhi::AdapterInfo>& adapters) {
  if (adapters.empty()) return "no Vulkan devices present";
  std::string text = std::to_string(adapters.size()) + " device(s):";
  for (const auto& a : adapters) {
    text += " [" + std::to_string(a.index) + "] " + a.name + " (" + a.type + (a.usable ? "" : ", unusable: " + a.unusableReason) + ")";
  }
  return text;
}

const rhi::AdapterInfo* firstOfType(const std::vector<rhi::AdapterInfo>& adapters, std::string_view type) {
  for (const auto& a : adapters) {
    if (a.usable && a.type == type) return &a;
  }
  return nullptr;
}

const rhi::AdapterInfo* firstGpu(const std::vector<rhi::AdapterInfo>& adapters) {
  if (const auto* discrete = firstOfType(adapters, "discrete")) return discrete;
  return firstOfType(adapters, "integrated");
}

}  // namespace

uint32_t selectAdapter(const std::vector<rhi::AdapterInfo>& adapters, std::string_view selector) {
  const std::string request(selector);
  if (selector == "auto") {
    if (const auto* gpu = firstGpu(adapters)) return gpu->index;
    if (const auto* cpu = firstOfType(adapters, "cpu")) return cpu->index;
    throw DeviceError("--device auto: no usable GPU or lavapipe device; " + adapterList(adapters));
  }
  if (selector == "gpu") {
    if (const auto* gpu = firstGpu(adapters)) return gpu->index;
    throw DeviceError("--device gpu: no usable discrete or integrated GPU; " + adapterList(adapters));
  }
  if (selector == "lavapipe") {
    if (const auto* cpu = firstOfType(adapters, "cpu")) return cpu->index;
    throw DeviceError("--device lavapipe: no usable CPU Vulkan device (install mesa-vulkan-drivers); " +
                      adapterList(adapters));
  }
  uint32_t index = 0;
  const auto [end, error] = std::from_chars(request.data(), request.data() + request.size(), index);
  if (error != std::errc() || end != request.data() + request.size() || request.empty()) {
    throw InputError("--device '" + request + "': expected auto, lavapipe, gpu or a device index");
  }
  if (index >= adapters.size()) {
    throw DeviceError("--device " + request + ": no such device index; " + adapterList(adapters));
  }
  if (!adapters[index].usable) {
    throw DeviceError("--device " + request + ": " + adapters[index].name + " is unusable: " +
                      adapters[index].unusableReason);
  }
  return index;
}

}  // namespace fgb::vulkan
