#include "command_buffer.hpp"

#include "translate.hpp"

#include <fgb/core/error.hpp>

#include <algorithm>
#include <vector>

namespace fgb::vulkan {
namespace {

VkBufferImageCopy wholeLevel(const TextureRecord& texture, uint64_t bufferOffset, uint32_t mipLevel) {
  VkBufferImageCopy region{};
  region.bufferOffset = bufferOffset;
  region.imageSubresource = {texture.aspect, mipLevel, 0, texture.desc.layers};
  region.imageExtent = {std::max(1u, texture.desc.extent.width >> mipLevel),
                        std::max(1u, texture.desc.extent.height >> mipLevel),
                        std::max(1u, texture.desc.extent.depth >> mipLevel)};
  return region;
}

}  // namespace

void VulkanCommandBuffer::begin(VkCommandBuffer cmd) {
  if (cmd != cmd_) graphicsSetBound_ = computeSetBound_ = VK_NULL_HANDLE;
  cmd_ = cmd;
}

void VulkanCommandBuffer::bindPipeline(rhi::PipelineId id) {
  const VkCommandBuffer cmd = recording();
  const PipelineRecord& record = device_->pipeline(id);
  vkCmdBindPipeline(cmd, record.bindPoint, record.pipeline.get());
  VkDescriptorSet& bound = record.bindPoint == VK_PIPELINE_BIND_POINT_GRAPHICS ? graphicsSetBound_ : computeSetBound_;
  const VkDescriptorSet set = set_ != VK_NULL_HANDLE ? set_ : device_->descriptors().set();
  if (bound == set) return;
  vkCmdBindDescriptorSets(cmd, record.bindPoint, device_->descriptors().pipelineLayout(), 0, 1, &set, 0, nullptr);
  bound = set;
}

void VulkanCommandBuffer::pushConstants(const void* data, uint32_t size, uint32_t offset) {
  const VkCommandBuffer cmd = recording();
  vkCmdPushConstants(cmd, device_->descriptors().pipelineLayout(), VK_SHADER_STAGE_ALL, offset, size, data);
}

void VulkanCommandBuffer::dispatch(uint32_t x, uint32_t y, uint32_t z) { vkCmdDispatch(recording(), x, y, z); }

void VulkanCommandBuffer::dispatchIndirect(rhi::BufferId arguments, uint64_t offset) {
  const VkCommandBuffer cmd = recording();
  vkCmdDispatchIndirect(cmd, vkBuffer(arguments), offset);
}

void VulkanCommandBuffer::memoryBarrier(graph::StageMask srcStages, graph::AccessMask srcAccess,
                                        graph::StageMask dstStages, graph::AccessMask dstAccess) {
  if (rendering_) throw DeviceError("memoryBarrier inside a render pass: split the work into graph nodes instead");
  const VkCommandBuffer cmd = recording();
  auto barrier = vkStruct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
  barrier.srcStageMask = toVkStages(srcStages);
  barrier.srcAccessMask = toVkAccess(srcAccess);
  barrier.dstStageMask = toVkStages(dstStages);
  barrier.dstAccessMask = toVkAccess(dstAccess);
  auto dependency = vkStruct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void VulkanCommandBuffer::setViewport(float x, float y, float width, float height) {
  const VkCommandBuffer cmd = recording();
  const VkViewport viewport{x, y, width, height, 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
}

void VulkanCommandBuffer::setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) {
  const VkCommandBuffer cmd = recording();
  const VkRect2D scissor{{x, y}, {width, height}};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void VulkanCommandBuffer::bindVertexBuffer(uint32_t binding, rhi::BufferId buffer, uint64_t offset) {
  const VkCommandBuffer cmd = recording();
  const VkBuffer handle = vkBuffer(buffer);
  vkCmdBindVertexBuffers(cmd, binding, 1, &handle, &offset);
}

void VulkanCommandBuffer::bindIndexBuffer(rhi::BufferId buffer, uint64_t offset, rhi::IndexType type) {
  const VkCommandBuffer cmd = recording();
  vkCmdBindIndexBuffer(cmd, vkBuffer(buffer), offset,
                       type == rhi::IndexType::Uint16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32);
}

void VulkanCommandBuffer::draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                               uint32_t firstInstance) {
  const VkCommandBuffer cmd = recording();
  vkCmdDraw(cmd, vertexCount, instanceCount, firstVertex, firstInstance);
}

void VulkanCommandBuffer::drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex,
                                      int32_t vertexOffset, uint32_t firstInstance) {
  const VkCommandBuffer cmd = recording();
  vkCmdDrawIndexed(cmd, indexCount, instanceCount, firstIndex, vertexOffset, firstInstance);
}

void VulkanCommandBuffer::drawIndexedIndirect(rhi::BufferId arguments, uint64_t offset, uint32_t drawCount,
                                              uint32_t stride) {
  const VkCommandBuffer cmd = recording();
  vkCmdDrawIndexedIndirect(cmd, vkBuffer(arguments), offset, drawCount, stride);
}

void VulkanCommandBuffer::drawIndexedIndirectCount(rhi::BufferId arguments, uint64_t offset, rhi::BufferId count,
                                                   uint64_t countOffset, uint32_t maxDrawCount, uint32_t stride) {
  const VkCommandBuffer cmd = recording();
  vkCmdDrawIndexedIndirectCount(cmd, vkBuffer(arguments), offset, vkBuffer(count), countOffset, maxDrawCount, stride);
}

void VulkanCommandBuffer::drawMeshTasksIndirectCount(rhi::BufferId arguments, uint64_t offset, rhi::BufferId count,
                                                     uint64_t countOffset, uint32_t maxDrawCount, uint32_t stride) {
  const VkCommandBuffer cmd = recording();
  if (vkCmdDrawMeshTasksIndirectCountEXT == nullptr)
    throw std::logic_error("drawMeshTasksIndirectCount: VK_EXT_mesh_shader is not enabled on this device");
  vkCmdDrawMeshTasksIndirectCountEXT(cmd, vkBuffer(arguments), offset, vkBuffer(count), countOffset, maxDrawCount,
                                     stride);
}

void VulkanCommandBuffer::copyBuffer(rhi::BufferId src, rhi::BufferId dst, std::span<const rhi::BufferCopy> regions) {
  const VkCommandBuffer cmd = recording();
  std::vector<VkBufferCopy> copies;
  copies.reserve(regions.size());
  for (const auto& r : regions) copies.push_back({r.srcOffset, r.dstOffset, r.size});
  vkCmdCopyBuffer(cmd, vkBuffer(src), vkBuffer(dst), static_cast<uint32_t>(copies.size()), copies.data());
}

void VulkanCommandBuffer::copyTextureToBuffer(rhi::TextureId src, rhi::BufferId dst, uint64_t dstOffset,
                                              uint32_t mipLevel) {
  const VkCommandBuffer cmd = recording();
  const TextureRecord& texture = device_->texture(src);
  const VkBufferImageCopy region = wholeLevel(texture, dstOffset, mipLevel);
  vkCmdCopyImageToBuffer(cmd, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, vkBuffer(dst), 1, &region);
}

void VulkanCommandBuffer::copyBufferToTexture(rhi::BufferId src, rhi::TextureId dst, uint64_t srcOffset,
                                              uint32_t mipLevel) {
  const VkCommandBuffer cmd = recording();
  const TextureRecord& texture = device_->texture(dst);
  const VkBufferImageCopy region = wholeLevel(texture, srcOffset, mipLevel);
  vkCmdCopyBufferToImage(cmd, vkBuffer(src), texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
}

void VulkanCommandBuffer::fillBuffer(rhi::BufferId buffer, uint64_t offset, uint64_t size, uint32_t value) {
  const VkCommandBuffer cmd = recording();
  vkCmdFillBuffer(cmd, vkBuffer(buffer), offset, size, value);
}

void VulkanCommandBuffer::clearTexture(rhi::TextureId id, const std::array<float, 4>& color) {
  const VkCommandBuffer cmd = recording();
  const TextureRecord& texture = device_->texture(id);
  const VkImageSubresourceRange range{texture.aspect, 0, texture.desc.mipLevels, 0, texture.desc.layers};
  if (graph::isDepthFormat(texture.desc.format)) {
    const VkClearDepthStencilValue value{color[0], 0};
    vkCmdClearDepthStencilImage(cmd, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
    return;
  }
  VkClearColorValue value{};
  std::copy(color.begin(), color.end(), value.float32);
  vkCmdClearColorImage(cmd, texture.image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
}

}  // namespace fgb::vulkan
