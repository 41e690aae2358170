// VulkanDevice: buffers, textures and samplers, and their slots in the shared descriptor set.
#include "device.hpp"
#include "translate.hpp"

#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>

#include <string>

namespace fgb::vulkan {
namespace {

template <class T>
uint64_t handleBits(T handle) {
  return reinterpret_cast<uint64_t>(handle);
}

uint32_t takeSlot(std::vector<uint32_t>& freeList, size_t size) {
  if (freeList.empty()) return static_cast<uint32_t>(size);
  const uint32_t slot = freeList.back();
  freeList.pop_back();
  return slot;
}

}  // namespace

VkBufferCreateInfo VulkanDevice::bufferInfo(const rhi::BufferDesc& desc) const {
  auto info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  info.size = desc.size;
  info.usage = toVkBufferUsage(desc.usage);
  // Buffers are shared by every queue family the device uses (as Granite does): no ownership
  // transfers for them, which costs nothing on current hardware (buffers are never compressed) and
  // lets a buffer written in one graph be read on another family in the next. Images stay
  // exclusive (concurrent images can lose compression); the frame graph transfers their ownership.
  if (queueFamilies_.size() > 1) {
    info.sharingMode = VK_SHARING_MODE_CONCURRENT;
    info.queueFamilyIndexCount = static_cast<uint32_t>(queueFamilies_.size());
    info.pQueueFamilyIndices = queueFamilies_.data();
  } else {
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  }
  return info;
}

VkImageCreateInfo VulkanDevice::imageInfo(const rhi::TextureDesc& desc) {
  auto info = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
  info.imageType = desc.extent.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = toVk(desc.format);
  info.extent = {desc.extent.width, desc.extent.height, desc.extent.depth};
  info.mipLevels = desc.mipLevels;
  info.arrayLayers = desc.layers;
  info.samples = toVkSamples(desc.samples);
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = toVkImageUsage(desc.usage, desc.format);
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return info;
}

rhi::BufferId VulkanDevice::createBuffer(const rhi::BufferDesc& desc) { return createBufferIn(desc, nullptr); }
rhi::TextureId VulkanDevice::createTexture(const rhi::TextureDesc& desc) { return createTextureIn(desc, nullptr); }

rhi::BufferId VulkanDevice::createBufferIn(const rhi::BufferDesc& desc, const Allocation* placement) {
  if (desc.size == 0) throw InputError("buffer '" + desc.name + "': size 0");
  const VkBufferCreateInfo info = bufferInfo(desc);
  VkBuffer handle = VK_NULL_HANDLE;
  check(vkCreateBuffer(device_, &info, nullptr, &handle), "vkCreateBuffer '" + desc.name + "'");
  BufferRecord record;
  record.buffer = Owned<VkBuffer>(device_, handle, vkDestroyBuffer);
  record.desc = desc;
  if (placement != nullptr) {
    record.allocation = *placement;
  } else {
    VkMemoryRequirements requirements{};
    vkGetBufferMemoryRequirements(device_, handle, &requirements);
    record.allocation = memory_->allocate(requirements, desc.memory, Tiling::Linear, "buffer '" + desc.name + "'");
    record.ownsMemory = true;
  }
  check(vkBindBufferMemory(device_, handle, record.allocation.memory, record.allocation.offset),
        "vkBindBufferMemory '" + desc.name + "'");
  setName(VK_OBJECT_TYPE_BUFFER, handleBits(handle), desc.name);
  if (desc.usage & rhi::kBufferStorage) record.storageIndex = descriptors_->addStorageBuffer(handle);

  const uint32_t slot = takeSlot(freeBuffers_, buffers_.size());
  if (slot == buffers_.size()) buffers_.emplace_back();
  buffers_[slot] = std::move(record);
  return rhi::BufferId{slot};
}

rhi::TextureId VulkanDevice::createTextureIn(const rhi::TextureDesc& desc, const Allocation* placement) {
  if (desc.format == graph::Format::Undefined) throw InputError("texture '" + desc.name + "': format undefined");
  const VkImageCreateInfo info = imageInfo(desc);
  VkImage image = VK_NULL_HANDLE;
  check(vkCreateImage(device_, &info, nullptr, &image), "vkCreateImage '" + desc.name + "'");
  TextureRecord record;
  record.image = Owned<VkImage>(device_, image, vkDestroyImage);
  record.desc = desc;
  record.aspect = aspectOf(desc.format);
  if (placement != nullptr) {
    record.allocation = *placement;
  } else {
    VkMemoryRequirements requirements{};
    vkGetImageMemoryRequirements(device_, image, &requirements);
    record.allocation = memory_->allocate(requirements, rhi::MemoryUsage::DeviceLocal, Tiling::Optimal,
                                          "texture '" + desc.name + "'");
    record.ownsMemory = true;
  }
  check(vkBindImageMemory(device_, image, record.allocation.memory, record.allocation.offset),
        "vkBindImageMemory '" + desc.name + "'");

  setName(VK_OBJECT_TYPE_IMAGE, handleBits(image), desc.name);
  constexpr rhi::TextureUsage kViewUsages =
      rhi::kTextureSampled | rhi::kTextureStorage | rhi::kTextureColorAttachment | rhi::kTextureDepthAttachment;
  if ((desc.usage & kViewUsages) != 0) createView(record);
  if (desc.usage & rhi::kTextureSampled) record.sampledIndex = descriptors_->addSampledTexture(record.view.get());
  if (desc.usage & rhi::kTextureStorage)
    record.storageIndex = descriptors_->addStorageTexture(record.view.get(), storageTextureBinding(desc.format));
  if ((desc.usage & rhi::kTextureSampled) && (desc.usage & rhi::kTextureStorage))
    record.sampledGeneralIndex = descriptors_->addSampledTexture(record.view.get(), VK_IMAGE_LAYOUT_GENERAL);

  const uint32_t slot = takeSlot(freeTextures_, textures_.size());
  if (slot == textures_.size()) textures_.emplace_back();
  textures_[slot] = std::move(record);
  return rhi::TextureId{slot};
}

// Images used only by copies need no view (and may not have one: no view-compatible usage).
void VulkanDevice::createView(TextureRecord& record) {
  const rhi::TextureDesc& desc = record.desc;
  auto viewInfo = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
  viewInfo.image = record.image.get();
  viewInfo.viewType = desc.extent.depth > 1 ? VK_IMAGE_VIEW_TYPE_3D
                      : desc.layers > 1     ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                            : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = toVk(desc.format);
  // Shaders see the depth aspect of depth-stencil images; attachments use the same view.
  viewInfo.subresourceRange = {graph::isDepthFormat(desc.format) ? VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT}
                                                                 : record.aspect,
                               0, desc.mipLevels, 0, desc.layers};
  VkImageView view = VK_NULL_HANDLE;
  check(vkCreateImageView(device_, &viewInfo, nullptr, &view), "vkCreateImageView '" + desc.name + "'");
  record.view = Owned<VkImageView>(device_, view, vkDestroyImageView);
  setName(VK_OBJECT_TYPE_IMAGE_VIEW, handleBits(view), desc.name + " view");
}

void VulkanDevice::destroyBuffer(rhi::BufferId id) {
  BufferRecord& record = buffers_.at(id.index);
  descriptors_->remove(Binding::StorageBuffers, record.storageIndex);
  if (record.ownsMemory) memory_->free(record.allocation);
  record = BufferRecord{};
  freeBuffers_.push_back(id.index);
}

void VulkanDevice::destroyTexture(rhi::TextureId id) {
  TextureRecord& record = textures_.at(id.index);
  descriptors_->remove(Binding::SampledTextures, record.sampledIndex);
  descriptors_->remove(Binding::SampledTextures, record.sampledGeneralIndex);
  descriptors_->remove(storageTextureBinding(record.desc.format), record.storageIndex);
  if (record.ownsMemory) memory_->free(record.allocation);
  record = TextureRecord{};
  freeTextures_.push_back(id.index);
}

rhi::SamplerId VulkanDevice::createSampler(const rhi::SamplerDesc& desc) {
  auto info = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
  info.magFilter = toVk(desc.magFilter);
  info.minFilter = toVk(desc.minFilter);
  info.mipmapMode = toVkMipmap(desc.mipFilter);
  info.addressModeU = info.addressModeV = info.addressModeW = toVk(desc.addressMode);
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(physical_, &features);
  info.anisotropyEnable = desc.maxAnisotropy > 1.0f && features.samplerAnisotropy;
  info.maxAnisotropy = info.anisotropyEnable ? desc.maxAnisotropy : 1.0f;
  info.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler = VK_NULL_HANDLE;
  check(vkCreateSampler(device_, &info, nullptr, &sampler), "vkCreateSampler '" + desc.name + "'");
  setName(VK_OBJECT_TYPE_SAMPLER, handleBits(sampler), desc.name);
  SamplerRecord record{Owned<VkSampler>(device_, sampler, vkDestroySampler), descriptors_->addSampler(sampler)};
  samplers_.push_back(std::move(record));
  return rhi::SamplerId{static_cast<uint32_t>(samplers_.size() - 1)};
}

std::span<std::byte> VulkanDevice::mapped(rhi::BufferId id) {
  const BufferRecord& record = buffer(id);
  // Device-local memory may be host-visible (CPU devices, resizable BAR); callers may not rely on it.
  if (record.desc.memory == rhi::MemoryUsage::DeviceLocal || record.allocation.mapped == nullptr) return {};
  return {record.allocation.mapped, record.desc.size};
}

const BufferRecord& VulkanDevice::buffer(rhi::BufferId id) const {
  if (id.index >= buffers_.size() || !buffers_[id.index].buffer) {
    throw std::out_of_range("no buffer with id " + std::to_string(id.index));
  }
  return buffers_[id.index];
}

const TextureRecord& VulkanDevice::texture(rhi::TextureId id) const {
  if (id.index >= textures_.size() || !textures_[id.index].image) {
    throw std::out_of_range("no texture with id " + std::to_string(id.index));
  }
  return textures_[id.index];
}

uint32_t VulkanDevice::storageBufferIndex(rhi::BufferId id) const { return buffer(id).storageIndex; }
uint32_t VulkanDevice::sampledTextureIndex(rhi::TextureId id) const { return texture(id).sampledIndex; }
uint32_t VulkanDevice::storageTextureIndex(rhi::TextureId id) const { return texture(id).storageIndex; }
uint32_t VulkanDevice::samplerIndex(rhi::SamplerId id) const { return samplers_.at(id.index).index; }

void VulkanDevice::initialiseFallbackDescriptors() {
  // Without partially-bound descriptors every slot must hold a valid resource: point them all at
  // dummies. The dummy image is cleared and left in GENERAL by a one-node transfer graph.
  const rhi::BufferId buffer = createBuffer({"dummy storage buffer", 256, rhi::kBufferStorage, rhi::MemoryUsage::DeviceLocal});
  const rhi::TextureId image = createTexture({"dummy texture", graph::Format::R8G8B8A8Unorm, {1, 1, 1}, 1, 1, 1,
                                              rhi::kTextureSampled | rhi::kTextureStorage | rhi::kTextureTransferDst});
  const rhi::SamplerId sampler = createSampler({"dummy sampler"});

  graph::FrameGraph init;
  const graph::ImportState before{graph::kStageNone, graph::kAccessNone, graph::Layout::Undefined};
  const graph::ImportState after{graph::kStageAllCommands, graph::kAccessShaderSampledRead, graph::Layout::General};
  auto dummy = init.importTexture("dummy texture", graph::TextureDesc{graph::Format::R8G8B8A8Unorm, {1, 1, 1}},
                                  rhi::external(image), before, after);
  auto node = init.addNode("Clear dummy descriptors", graph::NodeType::Transfer);
  dummy = node.write(dummy, graph::Access::TransferDst);
  node.setJob([dummy](graph::JobContext& context) {
    auto& rhi = rhi::rhiContext(context);
    rhi.cmd().clearTexture(rhi.texture(dummy), {0, 0, 0, 0});
  });
  auto executable = compile(std::move(init), {.name = "descriptor fallback init", .queues = 1, .timestamps = false});
  wait(execute(*executable, rhi::RunMode::Sequential, {}));
  descriptors_->fillWithDummies(buffers_[buffer.index].buffer.get(), textures_[image.index].view.get(),
                                textures_[image.index].view.get(), samplers_[sampler.index].sampler.get());
}

}  // namespace fgb::vulkan
