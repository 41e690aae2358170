#include "memory.hpp"

#include <fgb/core/error.hpp>

#include <string>

namespace fgb::vulkan {
namespace {

// Memory property flags wanted (in order of preference) for each usage.
std::vector<VkMemoryPropertyFlags> preferences(rhi::MemoryUsage usage) {
  constexpr VkMemoryPropertyFlags kLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  constexpr VkMemoryPropertyFlags kVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  constexpr VkMemoryPropertyFlags kCached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  switch (usage) {
    case rhi::MemoryUsage::DeviceLocal: return {kLocal, 0};
    case rhi::MemoryUsage::Upload: return {kVisible | kLocal, kVisible};  // resizable BAR first
    case rhi::MemoryUsage::Readback: return {kVisible | kCached, kVisible};
  }
  return {0};
}

}  // namespace

MemoryAllocator::MemoryAllocator(VkPhysicalDevice physical, VkDevice device) : device_(device) {
  vkGetPhysicalDeviceMemoryProperties(physical, &properties_);
}

uint32_t MemoryAllocator::chooseType(uint32_t typeBits, rhi::MemoryUsage usage, const std::string& what) const {
  for (const VkMemoryPropertyFlags wanted : preferences(usage)) {
    for (uint32_t type = 0; type < properties_.memoryTypeCount; ++type) {
      const bool allowed = (typeBits & (1u << type)) != 0;
      if (allowed && (properties_.memoryTypes[type].propertyFlags & wanted) == wanted) return type;
    }
  }
  throw DeviceError(what + ": no memory type fits (type bits 0x" + std::to_string(typeBits) + ")");
}

uint32_t MemoryAllocator::addBlock(uint64_t size, uint32_t type, Tiling tiling, const std::string& what) {
  auto info = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  info.allocationSize = size;
  info.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check(vkAllocateMemory(device_, &info, nullptr, &memory),
        "vkAllocateMemory(" + std::to_string(size >> 20) + " MiB) for " + what);
  auto block = std::make_unique<Block>(Block{Owned<VkDeviceMemory>(device_, memory, vkFreeMemory),
                                             rhi::RangeAllocator(size), type, tiling, nullptr});
  if (properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
    void* pointer = nullptr;
    check(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &pointer), "vkMapMemory for " + what);
    block->mapped = static_cast<std::byte*>(pointer);
  }
  blocks_.push_back(std::move(block));
  return static_cast<uint32_t>(blocks_.size() - 1);
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& requirements, rhi::MemoryUsage usage, Tiling tiling,
                                     const std::string& what) {
  const uint32_t type = chooseType(requirements.memoryTypeBits, usage, what);
  const auto carve = [&](uint32_t index) -> Allocation {
    Block& block = *blocks_[index];
    const auto offset = block.ranges.allocate(requirements.size, requirements.alignment);
    if (!offset) return {};
    return Allocation{index, *offset, requirements.size, block.memory.get(),
                      block.mapped ? block.mapped + *offset : nullptr};
  };
  for (uint32_t i = 0; i < blocks_.size(); ++i) {
    if (!blocks_[i] || blocks_[i]->type != type || blocks_[i]->tiling != tiling) continue;
    if (Allocation allocation = carve(i); allocation.valid()) return allocation;
  }
  // Large resources get a block of their own; everything else shares kBlockSize blocks.
  const uint64_t blockSize = requirements.size > kBlockSize / 2 ? requirements.size : kBlockSize;
  Allocation allocation = carve(addBlock(blockSize, type, tiling, what));
  if (!allocation.valid()) throw DeviceError(what + ": sub-allocation failed in a fresh memory block");
  return allocation;
}

void MemoryAllocator::free(const Allocation& allocation) {
  if (!allocation.valid()) return;
  auto& block = blocks_.at(allocation.block);
  block->ranges.free(allocation.offset);
  // Dedicated (oversized) blocks go back to the driver as soon as they are empty.
  if (block->ranges.empty() && block->ranges.size() > kBlockSize) block.reset();
}

uint64_t MemoryAllocator::reservedBytes() const {
  uint64_t total = 0;
  for (const auto& block : blocks_) total += block ? block->ranges.size() : 0;
  return total;
}

uint64_t MemoryAllocator::usedBytes() const {
  uint64_t total = 0;
  for (const auto& block : blocks_) total += block ? block->ranges.used() : 0;
  return total;
}

size_t MemoryAllocator::blockCount() const {
  size_t count = 0;
  for (const auto& block : blocks_) count += block ? 1 : 0;
  return count;
}

}  // namespace fgb::vulkan
