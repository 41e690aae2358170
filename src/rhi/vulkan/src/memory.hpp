// Device-memory sub-allocator: a few large VkDeviceMemory blocks per memory type, carved into
// aligned ranges (RangeAllocator). Buffers and images (linear vs optimal tiling) live in separate
// blocks, so bufferImageGranularity never matters between neighbours. Host-visible blocks are
// persistently mapped. Transient graph resources use allocate() for a whole aliasing heap and are
// bound at the plan's offsets inside it.
#pragma once

#include "vk.hpp"

#include <fgb/rhi/range_allocator.hpp>
#include <fgb/rhi/types.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace fgb::vulkan {

struct Allocation {
  uint32_t block = UINT32_MAX;
  uint64_t offset = 0;
  uint64_t size = 0;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  std::byte* mapped = nullptr;  // null unless host-visible
  [[nodiscard]] bool valid() const { return block != UINT32_MAX; }
};

enum class Tiling : uint8_t { Linear, Optimal };  // buffers vs images

class MemoryAllocator {
 public:
  static constexpr uint64_t kBlockSize = 64ull << 20;

  MemoryAllocator(VkPhysicalDevice physical, VkDevice device);

  // Throws DeviceError (naming `what`) when no memory type fits or the device is out of memory.
  Allocation allocate(const VkMemoryRequirements& requirements, rhi::MemoryUsage usage, Tiling tiling,
                      const std::string& what);
  void free(const Allocation& allocation);

  [[nodiscard]] uint64_t reservedBytes() const;  // sum of block sizes
  [[nodiscard]] uint64_t usedBytes() const;
  [[nodiscard]] size_t blockCount() const;

 private:
  struct Block {
    Owned<VkDeviceMemory> memory;
    rhi::RangeAllocator ranges;
    uint32_t type;
    Tiling tiling;
    std::byte* mapped;
  };

  uint32_t chooseType(uint32_t typeBits, rhi::MemoryUsage usage, const std::string& what) const;
  uint32_t addBlock(uint64_t size, uint32_t type, Tiling tiling, const std::string& what);

  VkDevice device_;
  VkPhysicalDeviceMemoryProperties properties_{};
  std::vector<std::unique_ptr<Block>> blocks_;  // null entries: released blocks
};

}  // namespace fgb::vulkan
