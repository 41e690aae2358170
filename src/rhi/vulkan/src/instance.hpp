// The Vulkan instance: loader through volk, optional validation (+ synchronization validation),
// and a debug-utils messenger that counts every warning/error message and prints it on stderr.
#pragma once

#include "vk.hpp"

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace fgb::vulkan {

class Instance {
 public:
  explicit Instance(bool validation);
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  [[nodiscard]] VkInstance get() const { return instance_; }
  [[nodiscard]] bool validation() const { return validation_; }
  [[nodiscard]] bool debugUtils() const { return debugUtils_; }
  [[nodiscard]] uint64_t messages() const { return messages_.load(); }
  [[nodiscard]] std::vector<std::string> log() const;
  [[nodiscard]] std::vector<VkPhysicalDevice> physicalDevices() const;

  // Called by the messenger; public only for the C callback.
  void record(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const VkDebugUtilsMessengerCallbackDataEXT& data);

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  bool validation_ = false;
  bool debugUtils_ = false;
  std::atomic<uint64_t> messages_{0};
  mutable std::mutex logMutex_;
  std::vector<std::string> log_;
};

// True when FGBENCH_VALIDATION is set to a value other than "0" or "".
bool validationRequestedByEnvironment();

}  // namespace fgb::vulkan
