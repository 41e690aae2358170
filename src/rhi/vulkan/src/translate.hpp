// One-to-one translations from the graph's and RHI's vocabulary to Vulkan (synchronization2).
#pragma once

#include "vk.hpp"

#include <fgb/graph/types.hpp>
#include <fgb/rhi/types.hpp>

namespace fgb::vulkan {

VkFormat toVk(graph::Format format);
VkFormat toVk(rhi::VertexFormat format);
VkImageAspectFlags aspectOf(graph::Format format);
VkSampleCountFlagBits toVkSamples(uint32_t samples);

VkPipelineStageFlags2 toVkStages(graph::StageMask stages);
// The access types a barrier recorded on a queue of a family with these flags may name (a
// transfer-only family: transfers, host and memory accesses; compute adds shader and indirect
// reads; graphics adds vertex input and attachments).
VkAccessFlags2 supportedAccess(VkQueueFlags family);
VkAccessFlags2 toVkAccess(graph::AccessMask access);
VkImageLayout toVk(graph::Layout layout);

VkBufferUsageFlags toVkBufferUsage(rhi::BufferUsage usage);
VkImageUsageFlags toVkImageUsage(rhi::TextureUsage usage, graph::Format format);

// The RHI usage a graph access needs on its resource.
rhi::BufferUsage bufferUsageFor(graph::Access access);
rhi::TextureUsage textureUsageFor(graph::Access access);

VkCompareOp toVk(rhi::CompareOp op);
VkPrimitiveTopology toVk(rhi::Topology topology);
VkCullModeFlags toVk(rhi::CullMode mode);
VkFilter toVk(rhi::Filter filter);
VkSamplerMipmapMode toVkMipmap(rhi::Filter filter);
VkSamplerAddressMode toVk(rhi::AddressMode mode);
VkAttachmentLoadOp toVk(graph::LoadOp op);
VkAttachmentStoreOp toVk(graph::StoreOp op);

}  // namespace fgb::vulkan
