// Scoped descriptor sets (see descriptors.hpp): one per graph node, exposing the device's
// resources outside the graph read-only, plus exactly the graph resources the node declared.
#include "descriptors.hpp"

#include <array>

namespace fgb::vulkan {
namespace {

constexpr uint32_t at(Binding binding) { return static_cast<uint32_t>(binding); }

constexpr std::array<VkDescriptorType, kBindingCount> kTypes = {
    VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,  VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
    VK_DESCRIPTOR_TYPE_SAMPLER,        VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE};
constexpr VkDescriptorType typeOf(Binding binding) { return kTypes[at(binding)]; }

bool inGraph(const std::vector<bool>* graphSlots, uint32_t slot) {
  return graphSlots && slot < graphSlots->size() && (*graphSlots)[slot];
}

// A sampled descriptor in GENERAL stands for storage access (Descriptors::addSampledTexture):
// hidden like storage textures unless the node declared it.
bool isSampledGeneral(Binding binding, const VkDescriptorImageInfo& entry) {
  return binding == Binding::SampledTextures && entry.imageLayout == VK_IMAGE_LAYOUT_GENERAL;
}

}  // namespace

ScopedSets::ScopedSets(Descriptors& owner, uint32_t count) : owner_(owner) {
  if (count == 0) return;
  const std::array<uint32_t, kBindingCount> capacities = {kMaxStorageBuffers,  kMaxSampledTextures,
                                                          kMaxStorageTextures, kMaxSamplers,
                                                          kMaxStorageBuffers,  kMaxInt64StorageTextures};
  std::array<VkDescriptorPoolSize, kBindingCount> sizes{};
  for (uint32_t i = 0; i < kBindingCount; ++i) sizes[i] = {kTypes[i], capacities[i] * count};
  auto info = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  info.flags = VK_DESCRIPTOR_POOL_CREATE_UPDATE_AFTER_BIND_BIT;
  info.maxSets = count;
  info.poolSizeCount = kBindingCount;
  info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vkCreateDescriptorPool(owner_.device_, &info, nullptr, &pool), "vkCreateDescriptorPool (scoped sets)");
  pool_ = Owned<VkDescriptorPool>(owner_.device_, pool, vkDestroyDescriptorPool);

  const std::vector<VkDescriptorSetLayout> layouts(count, owner_.setLayout_.get());
  auto allocate = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  allocate.descriptorPool = pool;
  allocate.descriptorSetCount = count;
  allocate.pSetLayouts = layouts.data();
  sets_.resize(count);
  check(vkAllocateDescriptorSets(owner_.device_, &allocate, sets_.data()), "vkAllocateDescriptorSets (scoped sets)");
  owner_.scoped_.push_back(this);
}

ScopedSets::~ScopedSets() { std::erase(owner_.scoped_, this); }

void ScopedSets::fill(uint32_t index, const DescriptorScope& scope) {
  const VkDescriptorSet set = sets_.at(index);
  std::vector<VkWriteDescriptorSet> writes;
  const auto add = [&](Binding binding, uint32_t slot) {
    auto write = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    write.dstSet = set;
    write.dstBinding = at(binding);
    write.dstArrayElement = slot;
    write.descriptorCount = 1;
    write.descriptorType = typeOf(binding);
    if (write.descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) write.pBufferInfo = &owner_.bufferEntries_[slot];
    else write.pImageInfo = &owner_.imageEntries_[at(binding)][slot];
    writes.push_back(write);
  };
  // Everything outside the graph (and not private to another one): buffers read-only, textures
  // sampled, every sampler.
  for (uint32_t slot = 0; slot < owner_.slots_[at(Binding::StorageBuffers)].next; ++slot) {
    if (owner_.bufferEntries_[slot].buffer != VK_NULL_HANDLE && !owner_.private_[0][slot] &&
        !inGraph(scope.graphBuffers, slot)) {
      add(Binding::StorageBuffers, slot);
    }
  }
  // (Storage textures outside the graph stay hidden: a shader writing one would be undeclared work;
  // so do sampled descriptors in GENERAL, which only a node holding the image as storage may use.)
  for (const Binding binding : {Binding::SampledTextures, Binding::Samplers}) {
    const std::vector<bool>* graphSlots = binding == Binding::SampledTextures ? scope.graphSampled : nullptr;
    const auto& entries = owner_.imageEntries_[at(binding)];
    for (uint32_t slot = 0; slot < owner_.slots_[at(binding)].next; ++slot) {
      const bool live = entries[slot].imageView != VK_NULL_HANDLE || entries[slot].sampler != VK_NULL_HANDLE;
      if (live && !owner_.private_[at(binding)][slot] && !inGraph(graphSlots, slot) &&
          !isSampledGeneral(binding, entries[slot])) {
        add(binding, slot);
      }
    }
  }
  // The node's declared resources: written buffers in both storage-buffer bindings.
  for (const uint32_t slot : scope.readBuffers) add(Binding::StorageBuffers, slot);
  for (const uint32_t slot : scope.writtenBuffers) {
    add(Binding::StorageBuffers, slot);
    add(Binding::WritableStorageBuffers, slot);
  }
  for (const uint32_t slot : scope.sampled) add(Binding::SampledTextures, slot);
  for (const uint32_t slot : scope.storageTextures) add(Binding::StorageTextures, slot);
  for (const uint32_t slot : scope.int64StorageTextures) add(Binding::Int64StorageTextures, slot);
  if (!writes.empty()) vkUpdateDescriptorSets(owner_.device_, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void ScopedSets::added(Binding binding, uint32_t slot) {
  // A resource created after the graph: outside it, so visible to every node (read-only).
  if (binding == Binding::StorageTextures || binding == Binding::Int64StorageTextures) return;
  if (isSampledGeneral(binding, owner_.imageEntries_[at(binding)][slot])) return;
  for (const VkDescriptorSet set : sets_) {
    auto write = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    write.dstSet = set;
    write.dstBinding = at(binding);
    write.dstArrayElement = slot;
    write.descriptorCount = 1;
    write.descriptorType = typeOf(binding);
    if (binding == Binding::StorageBuffers) write.pBufferInfo = &owner_.bufferEntries_[slot];
    else write.pImageInfo = &owner_.imageEntries_[at(binding)][slot];
    vkUpdateDescriptorSets(owner_.device_, 1, &write, 0, nullptr);
  }
}

}  // namespace fgb::vulkan
