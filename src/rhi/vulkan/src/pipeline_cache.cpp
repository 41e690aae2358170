#include "pipeline_cache.hpp"

#include <fgb/core/atomic_file.hpp>

#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

namespace fgb::vulkan {
namespace {

std::string fileName(const VkPhysicalDeviceProperties& properties) {
  return std::to_string(properties.vendorID) + "-" + std::to_string(properties.deviceID) + "-" +
         std::to_string(properties.driverVersion) + "-" + hexUuid(properties.pipelineCacheUUID) + ".vkpipelinecache";
}

std::vector<char> readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The header every driver writes (VkPipelineCacheHeaderVersionOne) must name this device.
bool headerMatches(const std::vector<char>& data, const VkPhysicalDeviceProperties& properties) {
  VkPipelineCacheHeaderVersionOne header{};
  if (data.size() < sizeof(header)) return false;
  std::memcpy(&header, data.data(), sizeof(header));
  return header.headerSize >= sizeof(header) && header.headerSize <= data.size() &&
         header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header.vendorID == properties.vendorID &&
         header.deviceID == properties.deviceID &&
         std::memcmp(header.pipelineCacheUUID, properties.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

}  // namespace

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties,
                             const std::filesystem::path& directory)
    : device_(device) {
  std::vector<char> data;
  if (!directory.empty()) {
    path_ = directory / fileName(properties);
    data = readFile(path_);
    if (!data.empty() && !headerMatches(data, properties)) {
      std::cerr << "warning: pipeline cache " << path_.string() << ": header does not match this device; starting empty\n";
      data.clear();
    }
    // Some drivers (lavapipe) keep nothing but the header in it: that is no warm cache.
    state_ = data.size() > sizeof(VkPipelineCacheHeaderVersionOne) ? "warm" : "cold";
  }
  auto info = vkStruct<VkPipelineCacheCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO);
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  VkPipelineCache cache = VK_NULL_HANDLE;
  check(vkCreatePipelineCache(device_, &info, nullptr, &cache), "vkCreatePipelineCache");
  cache_ = Owned<VkPipelineCache>(device_, cache, vkDestroyPipelineCache);
}

PipelineCache::~PipelineCache() {
  try {
    save();
  } catch (const std::exception& e) {
    // Losing the cache costs the next run its compile time, nothing else: warn, do not fail.
    std::cerr << "warning: pipeline cache " << path_.string() << " not saved: " << e.what() << "\n";
  }
}

void PipelineCache::save() const {
  if (path_.empty()) return;
  size_t size = 0;
  check(vkGetPipelineCacheData(device_, cache_.get(), &size, nullptr), "vkGetPipelineCacheData");
  std::vector<std::byte> data(size);
  check(vkGetPipelineCacheData(device_, cache_.get(), &size, data.data()), "vkGetPipelineCacheData");
  data.resize(size);
  std::filesystem::create_directories(path_.parent_path());
  writeFileAtomic(path_, data);
}

}  // namespace fgb::vulkan
