// The one descriptor set every pipeline shares (set 0, see shaders/include/bindless.glsl) and the
// one pipeline layout (set 0 + push constants). Bindless where the device allows it (update-after-
// bind, partially bound): slots are written whenever a resource is created. Fallback otherwise:
// every slot is pre-filled with a dummy resource and writes wait until the GPU is idle.
#pragma once

#include "vk.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace fgb::vulkan {

// Capacities; must match the FGB_MAX_* macros in shaders/include/bindless.glsl.
inline constexpr uint32_t kMaxStorageBuffers = 65536;
inline constexpr uint32_t kMaxSampledTextures = 4096;
inline constexpr uint32_t kMaxStorageTextures = 1024;
inline constexpr uint32_t kMaxSamplers = 64;

enum class Binding : uint32_t { StorageBuffers = 0, SampledTextures = 1, StorageTextures = 2, Samplers = 3 };

// Can this device run the bindless path?
bool supportsBindless(VkPhysicalDevice physical);

class Descriptors {
 public:
  // `beforeWrite` runs before a fallback-mode write (the device waits for idle there).
  Descriptors(VkDevice device, bool bindless, std::function<void()> beforeWrite);

  [[nodiscard]] bool bindless() const { return bindless_; }
  [[nodiscard]] VkDescriptorSet set() const { return set_; }
  [[nodiscard]] VkPipelineLayout pipelineLayout() const { return pipelineLayout_.get(); }

  uint32_t addStorageBuffer(VkBuffer buffer);
  uint32_t addSampledTexture(VkImageView view);
  uint32_t addStorageTexture(VkImageView view);
  uint32_t addSampler(VkSampler sampler);
  void remove(Binding binding, uint32_t index);

  // Fallback mode: points every slot at the dummies (views in GENERAL layout).
  void fillWithDummies(VkBuffer buffer, VkImageView sampledView, VkImageView storageView, VkSampler sampler);

 private:
  struct Slots {
    uint32_t capacity = 0;
    uint32_t next = 0;
    std::vector<uint32_t> freed;
  };
  uint32_t take(Binding binding);
  void write(Binding binding, uint32_t index, const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image);
  void createLayout();
  void createPool();

  VkDevice device_;
  bool bindless_;
  std::function<void()> beforeWrite_;
  Owned<VkDescriptorSetLayout> setLayout_;
  Owned<VkDescriptorPool> pool_;
  Owned<VkPipelineLayout> pipelineLayout_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Slots slots_[4];
};

}  // namespace fgb::vulkan
