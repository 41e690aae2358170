// The CommandBuffer a job records into: a VkCommandBuffer owned by the executor, plus the device
// tables to resolve RHI ids. Binds the node's descriptor set lazily per bind point. The executor's
// per-node prologue (queued barriers, debug label, begin timestamp) runs lazily too, right before
// the node's first command: a node whose job records nothing costs no commands at all.
#pragma once

#include "device.hpp"

#include <fgb/rhi/command_buffer.hpp>

namespace fgb::vulkan {

class VulkanCommandBuffer final : public rhi::CommandBuffer {
 public:
  explicit VulkanCommandBuffer(const VulkanDevice& device) : device_(&device) {}

  // Starts recording a new node into `cmd` (set bound state is kept within one VkCommandBuffer).
  void begin(VkCommandBuffer cmd);
  [[nodiscard]] VkCommandBuffer get() const { return cmd_; }
  // The descriptor set the next pipelines see (a node's scoped set); null: the shared set.
  void useSet(VkDescriptorSet set) { set_ = set; }
  // Something else bound a descriptor set at the compute bind point: bind the node's again.
  void forgetComputeSet() { computeSetBound_ = VK_NULL_HANDLE; }

  using Prologue = void (*)(void* context);
  // A node starts: `prologue(context)` runs before its first command (or at once via start()).
  // `rendering`: the prologue begins a render pass (no pipeline barriers inside it).
  void beginNode(Prologue prologue, void* context, bool rendering) {
    prologue_ = prologue;
    prologueContext_ = context;
    started_ = false;
    rendering_ = rendering;
  }
  void start() {
    if (started_) return;
    started_ = true;
    prologue_(prologueContext_);
  }
  // The node ends; true if it recorded anything (its prologue ran).
  bool endNode() { return started_; }

  void bindPipeline(rhi::PipelineId pipeline) override;
  void pushConstants(const void* data, uint32_t size, uint32_t offset) override;
  void dispatch(uint32_t x, uint32_t y, uint32_t z) override;
  void dispatchIndirect(rhi::BufferId arguments, uint64_t offset) override;
  void memoryBarrier(graph::StageMask srcStages, graph::AccessMask srcAccess, graph::StageMask dstStages,
                     graph::AccessMask dstAccess) override;
  void setViewport(float x, float y, float width, float height) override;
  void setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) override;
  void bindVertexBuffer(uint32_t binding, rhi::BufferId buffer, uint64_t offset) override;
  void bindIndexBuffer(rhi::BufferId buffer, uint64_t offset, rhi::IndexType type) override;
  void draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex, uint32_t firstInstance) override;
  void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t vertexOffset,
                   uint32_t firstInstance) override;
  void drawIndexedIndirect(rhi::BufferId arguments, uint64_t offset, uint32_t drawCount, uint32_t stride) override;
  void drawMeshTasksIndirectCount(rhi::BufferId arguments, uint64_t offset, rhi::BufferId count, uint64_t countOffset,
                                  uint32_t maxDrawCount, uint32_t stride) override;
  void drawIndexedIndirectCount(rhi::BufferId arguments, uint64_t offset, rhi::BufferId count, uint64_t countOffset,
                                uint32_t maxDrawCount, uint32_t stride) override;
  void copyBuffer(rhi::BufferId src, rhi::BufferId dst, std::span<const rhi::BufferCopy> regions) override;
  void copyTextureToBuffer(rhi::TextureId src, rhi::BufferId dst, uint64_t dstOffset, uint32_t mipLevel) override;
  void copyBufferToTexture(rhi::BufferId src, rhi::TextureId dst, uint64_t srcOffset, uint32_t mipLevel) override;
  void fillBuffer(rhi::BufferId buffer, uint64_t offset, uint64_t size, uint32_t value) override;
  void clearTexture(rhi::TextureId texture, const std::array<float, 4>& color) override;

 private:
  VkBuffer vkBuffer(rhi::BufferId id) const { return device_->buffer(id).buffer.get(); }
  // Every recording method begins with this.
  VkCommandBuffer recording() {
    if (!started_) [[unlikely]] start();
    return cmd_;
  }

  const VulkanDevice* device_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkDescriptorSet graphicsSetBound_ = VK_NULL_HANDLE;  // set bound at each bind point
  VkDescriptorSet computeSetBound_ = VK_NULL_HANDLE;
  Prologue prologue_ = nullptr;
  void* prologueContext_ = nullptr;
  bool started_ = true;
  bool rendering_ = false;
};

}  // namespace fgb::vulkan
