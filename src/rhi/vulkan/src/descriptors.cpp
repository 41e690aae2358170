#include "descriptors.hpp"

#include <fgb/core/error.hpp>
#include <fgb/rhi/types.hpp>

#include <algorithm>
#include <array>
#include <string>

namespace fgb::vulkan {
namespace {

constexpr std::array<VkDescriptorType, kBindingCount> kTypes = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
    VK_DESCRIPTOR_TYPE_SAMPLER,        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
constexpr std::array<uint32_t, kBindingCount> kCapacities = {kMaxStorageBuffers,  kMaxSampledTextures,
                                                             kMaxStorageTextures, kMaxSamplers,
                                                             kMaxStorageBuffers,  kMaxInt64StorageTextures};
constexpr std::array<const char*, kBindingCount> kNames = {"storage buffers",          "sampled textures",
                                                           "storage textures",         "samplers",
                                                           "writable storage buffers", "R64 storage textures"};

uint32_t index(Binding binding) { return static_cast<uint32_t>(binding); }

}  // namespace

Binding storageTextureBinding(graph::Format format) {
  return format == graph::Format::R64Uint ? Binding::Int64StorageTextures : Binding::StorageTextures;
}

bool supportsBindless(VkPhysicalDevice physical) {
  auto v12 = vkStruct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
  auto features = vkStruct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2);
  features.pNext = &v12;
  vkGetPhysicalDeviceFeatures2(physical, &features);
  return v12.descriptorIndexing && v12.descriptorBindingPartiallyBound &&
         v12.descriptorBindingStorageBufferUpdateAfterBind && v12.descriptorBindingSampledImageUpdateAfterBind &&
         v12.descriptorBindingStorageImageUpdateAfterBind && v12.descriptorBindingUpdateUnusedWhilePending;
}

Descriptors::Descriptors(VkDevice device, bool bindless, std::function<void()> beforeWrite)
    : device_(device), bindless_(bindless), beforeWrite_(std::move(beforeWrite)) {
  bufferEntries_.assign(kMaxStorageBuffers, VkDescriptorBufferInfo{});
  for (const Binding binding : kSlotBindings) {
    const uint32_t i = index(binding);
    slots_[i].capacity = kCapacities[i];
    private_[i].assign(kCapacities[i], false);
    if (kTypes[i] != VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
      imageEntries_[i].assign(kCapacities[i], VkDescriptorImageInfo{});
  }
  createLayout();
  createPool();
}

void Descriptors::createLayout() {
  std::array<VkDescriptorSetLayoutBinding, kBindingCount> bindings{};
  std::array<VkDescriptorBindingFlags, kBindingCount> flags{};
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    bindings[i] = {i, kTypes[i], kCapacities[i], VK_SHADER_STAGE_ALL, nullptr};
    // Bindless: slots may be empty and may be written while command buffers using the set are pending.
    flags[i] = bindless_ ? VK_DESCRIPTOR_BINDING_PARTIALLY_BOUND_BIT | VK_DESCRIPTOR_BINDING_UPDATE_AFTER_BIND_BIT |
                               VK_DESCRIPTOR_BINDING_UPDATE_UNUSED_WHILE_PENDING_BIT
                         : 0;
  }
  auto flagInfo = vkStruct<VkDescriptorSetLayoutBindingFlagsCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_BINDING_FLAGS_CREATE_INFO);
  flagInfo.bindingCount = kBindingCount;
  flagInfo.pBindingFlags = flags.data();
  auto info = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  info.pNext = &flagInfo;
  info.flags = bindless_ ? VK_DESCRIPTOR_SET_LAYOUT_CREATE_UPDATE_AFTER_BIND_POOL_BIT : 0;
  info.bindingCount = kBindingCount;
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  check(vkCreateDescriptorSetLayout(device_, &info, nullptr, &layout), "vkCreateDescriptorSetLayout (bindless set)");
  setLayout_ = Owned<VkDescriptorSetLayout>(device_, layout, vkDestroyDescriptorSetLayout);

  const VkPushConstantRange push{VK_SHADER_STAGE_ALL, 0, rhi::kPushConstantBytes};
  pipelineLayout_ = createPipelineLayout(device_, layout, push, "bindless set");
}

void Descriptors::createPool() {
  std::array<VkDescriptorPoolSize, kBindingCount> sizes{};
  for (uint32_t i = 0; i < kBindingCount; ++i) sizes[i] = {kTypes[i], kCapacities[i]};
  auto info = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  info.flags = bindless_ ? VK_DESCRIPTOR_POOL_CREATE_UPDATE_AFTER_BIND_BIT : 0;
  info.maxSets = 1;
  info.poolSizeCount = kBindingCount;
  info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vkCreateDescriptorPool(device_, &info, nullptr, &pool), "vkCreateDescriptorPool (bindless set)");
  pool_ = Owned<VkDescriptorPool>(device_, pool, vkDestroyDescriptorPool);

  const VkDescriptorSetLayout layout = setLayout_.get();
  auto allocate = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  allocate.descriptorPool = pool;
  allocate.descriptorSetCount = 1;
  allocate.pSetLayouts = &layout;
  check(vkAllocateDescriptorSets(device_, &allocate, &set_), "vkAllocateDescriptorSets (bindless set)");
}

uint32_t Descriptors::take(Binding binding) {
  Slots& slots = slots_[index(binding)];
  if (!slots.freed.empty()) {
    const uint32_t slot = slots.freed.back();
    slots.freed.pop_back();
    return slot;
  }
  if (slots.next == slots.capacity) {
    throw DeviceError(std::string("descriptor table full: more than ") + std::to_string(slots.capacity) + " " +
                      kNames[index(binding)]);
  }
  return slots.next++;
}

void Descriptors::write(Binding binding, uint32_t slot, const VkDescriptorBufferInfo* buffer,
                        const VkDescriptorImageInfo* image) {
  if (!bindless_ && beforeWrite_) beforeWrite_();
  auto write = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
  write.dstSet = set_;
  write.dstBinding = index(binding);
  write.dstArrayElement = slot;
  write.descriptorCount = 1;
  write.descriptorType = kTypes[index(binding)];
  write.pBufferInfo = buffer;
  write.pImageInfo = image;
  vkUpdateDescriptorSets(device_, 1, &write, 0, nullptr);
}

uint32_t Descriptors::addStorageBuffer(VkBuffer buffer) {
  const uint32_t slot = take(Binding::StorageBuffers);
  const VkDescriptorBufferInfo info{buffer, 0, VK_WHOLE_SIZE};
  write(Binding::StorageBuffers, slot, &info, nullptr);
  write(Binding::WritableStorageBuffers, slot, &info, nullptr);
  added(Binding::StorageBuffers, slot, &info, nullptr);
  return slot;
}

uint32_t Descriptors::addSampledTexture(VkImageView view, VkImageLayout layout) {
  const uint32_t slot = take(Binding::SampledTextures);
  const VkDescriptorImageInfo info{VK_NULL_HANDLE, view, layout};
  write(Binding::SampledTextures, slot, nullptr, &info);
  added(Binding::SampledTextures, slot, nullptr, &info);
  return slot;
}

uint32_t Descriptors::addStorageTexture(VkImageView view, Binding binding) {
  const uint32_t slot = take(binding);
  const VkDescriptorImageInfo info{VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
  write(binding, slot, nullptr, &info);
  added(binding, slot, nullptr, &info);
  return slot;
}

uint32_t Descriptors::addSampler(VkSampler sampler) {
  const uint32_t slot = take(Binding::Samplers);
  const VkDescriptorImageInfo info{sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
  write(Binding::Samplers, slot, nullptr, &info);
  added(Binding::Samplers, slot, nullptr, &info);
  return slot;
}

void Descriptors::remove(Binding binding, uint32_t slot) {
  if (slot == rhi::kInvalidId) return;
  // Bindless slots may stay stale (partially bound, never accessed); fallback ones keep their
  // last (valid) resource until reused, which is fine because the resource outlives its use.
  slots_[index(binding)].freed.push_back(slot);
  if (!bindless_) return;
  if (binding == Binding::StorageBuffers) bufferEntries_[slot] = {};
  else imageEntries_[index(binding)][slot] = {};
}

void Descriptors::added(Binding binding, uint32_t slot, const VkDescriptorBufferInfo* buffer,
                        const VkDescriptorImageInfo* image) {
  if (!bindless_) return;
  if (buffer) bufferEntries_[slot] = *buffer;
  else imageEntries_[index(binding)][slot] = *image;
  private_[index(binding)][slot] = creatingPrivate_;
  if (creatingPrivate_) return;
  for (ScopedSets* scoped : scoped_) scoped->added(binding, slot);
}

void Descriptors::fillWithDummies(VkBuffer buffer, VkImageView sampledView, VkImageView storageView, VkSampler sampler) {
  const VkDescriptorBufferInfo bufferInfo{buffer, 0, VK_WHOLE_SIZE};
  const VkDescriptorImageInfo sampledInfo{VK_NULL_HANDLE, sampledView, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo storageInfo{VK_NULL_HANDLE, storageView, VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo samplerInfo{sampler, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_UNDEFINED};
  std::vector<VkDescriptorBufferInfo> buffers(kMaxStorageBuffers, bufferInfo);
  std::vector<VkDescriptorImageInfo> sampled(kMaxSampledTextures, sampledInfo);
  // Binding 5 (R64 storage textures) gets the same dummy: only its slots of real R64 textures are
  // ever accessed.
  std::vector<VkDescriptorImageInfo> storage(std::max(kMaxStorageTextures, kMaxInt64StorageTextures), storageInfo);
  std::vector<VkDescriptorImageInfo> samplers(kMaxSamplers, samplerInfo);
  std::array<VkWriteDescriptorSet, kBindingCount> writes{};
  for (uint32_t i = 0; i < kBindingCount; ++i) {
    writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    writes[i].dstSet = set_;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = kCapacities[i];
    writes[i].descriptorType = kTypes[i];
  }
  writes[0].pBufferInfo = buffers.data();
  writes[1].pImageInfo = sampled.data();
  writes[2].pImageInfo = storage.data();
  writes[3].pImageInfo = samplers.data();
  writes[4].pBufferInfo = buffers.data();
  writes[5].pImageInfo = storage.data();
  vkUpdateDescriptorSets(device_, kBindingCount, writes.data(), 0, nullptr);
}

}  // namespace fgb::vulkan
