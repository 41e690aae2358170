// An on-disk VkPipelineCache: loaded when the device is created, saved (atomically) when it goes,
// one file per device and driver build (vendor, device, driver version, pipelineCacheUUID in the
// name), so a second run compiles no pipeline the driver has already compiled. A file whose header
// does not match this device is ignored (the driver starts an empty cache), never trusted.
#pragma once

#include "vk.hpp"

#include <filesystem>
#include <string>

namespace fgb::vulkan {

class PipelineCache {
 public:
  // `directory` empty: an in-memory cache only (nothing read or written).
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties, const std::filesystem::path& directory);
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  [[nodiscard]] VkPipelineCache get() const { return cache_.get(); }
  // "off" (no directory), "cold" (no pipeline data on disk: compiled from scratch), "warm".
  [[nodiscard]] const std::string& state() const { return state_; }
  void save() const;

 private:
  VkDevice device_;
  std::filesystem::path path_;
  Owned<VkPipelineCache> cache_;
  std::string state_ = "off";
};

}  // namespace fgb::vulkan
