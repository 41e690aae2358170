// The one descriptor set layout every pipeline shares (set 0: binding numbers and capacities from
// fgb/rhi/shared/bindless.h, which shaders include too) and the one pipeline layout (set 0 + push
// constants). Bindless where the device allows it
// (update-after-bind, partially bound): slots are written whenever a resource is created. Fallback
// otherwise: every slot is pre-filled with a dummy resource and writes wait until the GPU is idle.
//
// R64Uint storage textures have a binding of their own (5): shaders declare them as u64image2D,
// and a second image variable on binding 2 would make validation count every storage texture a
// node uses as read by one variable and written by the other (both variables see every
// descriptor of the binding they alias).
//
// Storage buffers appear twice, at the same slot: binding 0 for blocks the shader only reads
// (`readonly`), binding 4 for blocks it may write. Bindless devices also get *scoped* sets
// (ScopedSets, one per graph node): same layout and slot numbers, but exposing only the resources
// outside the graph (read-only) plus those the node declared, with write access only where it
// declared a write. Validation (synchronization validation in particular) treats every valid
// descriptor of a statically used binding as accessed, so the shared set would make every node
// look like it touches every resource. Scoped sets are built only when validation is on.
#pragma once

#include "vk.hpp"

#include <fgb/graph/format.hpp>
#include <fgb/rhi/shared/bindless.h>

#include <cstdint>
#include <functional>
#include <vector>

namespace fgb::vulkan {

// Capacities.
inline constexpr uint32_t kMaxStorageBuffers = FGB_MAX_STORAGE_BUFFERS;  // per storage-buffer binding (0 and 4)
inline constexpr uint32_t kMaxSampledTextures = FGB_MAX_SAMPLED_TEXTURES;
inline constexpr uint32_t kMaxStorageTextures = FGB_MAX_STORAGE_TEXTURES;
inline constexpr uint32_t kMaxSamplers = FGB_MAX_SAMPLERS;
inline constexpr uint32_t kMaxInt64StorageTextures = FGB_MAX_INT64_STORAGE_TEXTURES;

enum class Binding : uint32_t {
  StorageBuffers = FGB_BINDING_STORAGE_BUFFERS,  // read-only blocks
  SampledTextures = FGB_BINDING_SAMPLED_TEXTURES,
  StorageTextures = FGB_BINDING_STORAGE_TEXTURES,
  Samplers = FGB_BINDING_SAMPLERS,
  WritableStorageBuffers = FGB_BINDING_WRITABLE_STORAGE_BUFFERS,  // same slots as StorageBuffers
  Int64StorageTextures = FGB_BINDING_INT64_STORAGE_TEXTURES,      // R64Uint (64-bit image atomics)
};
inline constexpr uint32_t kBindingCount = FGB_BINDING_COUNT;
// The storage-texture binding of a format.
Binding storageTextureBinding(graph::Format format);

class ScopedSets;

// What one scoped set exposes, as slots of the shared set.
struct DescriptorScope {
  // Slots of every resource the graph uses (hidden unless listed below). Storage textures are
  // exposed only where declared, so they need no such list.
  const std::vector<bool>* graphBuffers = nullptr;
  const std::vector<bool>* graphSampled = nullptr;
  // Slots the node declared.
  std::vector<uint32_t> readBuffers;
  std::vector<uint32_t> writtenBuffers;
  std::vector<uint32_t> sampled;
  std::vector<uint32_t> storageTextures;
  std::vector<uint32_t> int64StorageTextures;
};

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
  // A sampled descriptor in GENERAL is for nodes that hold the image as storage: scoped sets expose
  // it only to nodes that declared so (graph::Access::StorageSampledWrite), never as a resource
  // outside the graph.
  uint32_t addSampledTexture(VkImageView view, VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  uint32_t addStorageTexture(VkImageView view, Binding binding);  // StorageTextures or Int64StorageTextures
  uint32_t addSampler(VkSampler sampler);
  void remove(Binding binding, uint32_t index);

  // While a graph creates its transient resources: they are private to it (exposed only to the
  // nodes that declare them, never to other graphs' scoped sets).
  void setCreatingPrivate(bool on) { creatingPrivate_ = on; }

  // Fallback mode: points every slot at the dummies (views in GENERAL layout).
  void fillWithDummies(VkBuffer buffer, VkImageView sampledView, VkImageView storageView, VkSampler sampler);
  // Bindings with slots of their own (WritableStorageBuffers shares StorageBuffers' slots).
  static constexpr Binding kSlotBindings[] = {Binding::StorageBuffers, Binding::SampledTextures,
                                              Binding::StorageTextures, Binding::Samplers,
                                              Binding::Int64StorageTextures};

 private:
  friend class ScopedSets;
  struct Slots {
    uint32_t capacity = 0;
    uint32_t next = 0;
    std::vector<uint32_t> freed;
  };
  uint32_t take(Binding binding);
  void write(Binding binding, uint32_t index, const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image);
  void added(Binding binding, uint32_t slot, const VkDescriptorBufferInfo* buffer, const VkDescriptorImageInfo* image);
  void createLayout();
  void createPool();

  VkDevice device_;
  bool bindless_;
  std::function<void()> beforeWrite_;
  Owned<VkDescriptorSetLayout> setLayout_;
  Owned<VkDescriptorPool> pool_;
  Owned<VkPipelineLayout> pipelineLayout_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  Slots slots_[kBindingCount];  // by Binding (WritableStorageBuffers unused)
  // Bindless: what each slot holds (null handle: free), to fill scoped sets.
  std::vector<VkDescriptorBufferInfo> bufferEntries_;
  std::vector<VkDescriptorImageInfo> imageEntries_[kBindingCount];  // by Binding (the image ones)
  // By Binding: the slot holds a graph's transient.
  std::vector<bool> private_[kBindingCount];
  bool creatingPrivate_ = false;
  std::vector<ScopedSets*> scoped_;  // live scoped sets: new resources are added to them too
};

// Descriptor sets of the shared layout exposing only part of the shared set (bindless only; see
// the top of this file). Owned by a compiled graph; new device resources (outside every graph
// that already exists) are added to them as they are created.
class ScopedSets {
 public:
  ScopedSets(Descriptors& owner, uint32_t count);
  ~ScopedSets();
  ScopedSets(const ScopedSets&) = delete;
  ScopedSets& operator=(const ScopedSets&) = delete;

  [[nodiscard]] VkDescriptorSet set(uint32_t index) const { return sets_.at(index); }
  void fill(uint32_t index, const DescriptorScope& scope);

 private:
  friend class Descriptors;
  void added(Binding binding, uint32_t slot);

  Descriptors& owner_;
  Owned<VkDescriptorPool> pool_;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace fgb::vulkan
