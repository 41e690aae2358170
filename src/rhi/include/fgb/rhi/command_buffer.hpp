// What a node's job records into. There is no way to create, begin, end or submit one: the
// executor hands each job the command buffer of its node, already inside the node's barriers (and
// inside vkCmdBeginRendering for graphics nodes). Textures a node uses are in the layout its
// declared access implies (copies: transfer src/dst layouts).
#pragma once

#include <fgb/rhi/types.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>

namespace fgb::rhi {

struct BufferCopy {
  uint64_t srcOffset = 0;
  uint64_t dstOffset = 0;
  uint64_t size = 0;
};

class CommandBuffer {
 public:
  virtual ~CommandBuffer() = default;

  virtual void bindPipeline(PipelineId pipeline) = 0;
  virtual void pushConstants(const void* data, uint32_t size, uint32_t offset = 0) = 0;
  template <class T>
  void push(const T& value) {
    static_assert(sizeof(T) <= kPushConstantBytes, "push constants exceed the shared layout");
    pushConstants(&value, sizeof(T));
  }

  virtual void dispatch(uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1) = 0;
  virtual void dispatchIndirect(BufferId arguments, uint64_t offset = 0) = 0;
  // A dependency between two commands of this node on memory the node declared (a compute node
  // whose second dispatch reads what its first wrote). The graph orders nodes; only work inside
  // one node needs this. Not inside a render pass: compute and transfer nodes only (throws).
  virtual void memoryBarrier(graph::StageMask srcStages, graph::AccessMask srcAccess, graph::StageMask dstStages,
                             graph::AccessMask dstAccess) = 0;
  // The common case: compute shader writes made visible to compute shader reads and writes, sampled
  // reads included (a node that samples what it wrote: graph::Access::StorageSampledWrite).
  void computeBarrier() {
    memoryBarrier(graph::kStageComputeShader, graph::kAccessShaderStorageWrite, graph::kStageComputeShader,
                  graph::kAccessShaderStorageRead | graph::kAccessShaderSampledRead | graph::kAccessShaderStorageWrite);
  }

  virtual void setViewport(float x, float y, float width, float height) = 0;
  virtual void setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) = 0;
  virtual void bindVertexBuffer(uint32_t binding, BufferId buffer, uint64_t offset = 0) = 0;
  virtual void bindIndexBuffer(BufferId buffer, uint64_t offset, IndexType type) = 0;
  virtual void draw(uint32_t vertexCount, uint32_t instanceCount = 1, uint32_t firstVertex = 0,
                    uint32_t firstInstance = 0) = 0;
  virtual void drawIndexed(uint32_t indexCount, uint32_t instanceCount = 1, uint32_t firstIndex = 0,
                           int32_t vertexOffset = 0, uint32_t firstInstance = 0) = 0;
  virtual void drawIndexedIndirect(BufferId arguments, uint64_t offset, uint32_t drawCount, uint32_t stride) = 0;
  virtual void drawIndexedIndirectCount(BufferId arguments, uint64_t offset, BufferId count, uint64_t countOffset,
                                        uint32_t maxDrawCount, uint32_t stride) = 0;
  // Mesh pipelines (Device::meshShaders()): up to maxDrawCount draws, each a
  // VkDrawMeshTasksIndirectCommandEXT (three uint32 workgroup counts) at `stride` bytes from the
  // last, their number read from `count` (vkCmdDrawMeshTasksIndirectCountEXT). Devices without
  // mesh shaders throw std::logic_error.
  virtual void drawMeshTasksIndirectCount(BufferId /*arguments*/, uint64_t /*offset*/, BufferId /*count*/,
                                          uint64_t /*countOffset*/, uint32_t /*maxDrawCount*/, uint32_t /*stride*/) {
    throw std::logic_error("drawMeshTasksIndirectCount on a device without mesh shaders");
  }

  virtual void copyBuffer(BufferId src, BufferId dst, std::span<const BufferCopy> regions) = 0;
  void copyBuffer(BufferId src, BufferId dst, uint64_t size) {
    const BufferCopy region{0, 0, size};
    copyBuffer(src, dst, std::span(&region, 1));
  }
  // Whole mip level, tightly packed rows.
  virtual void copyTextureToBuffer(TextureId src, BufferId dst, uint64_t dstOffset = 0, uint32_t mipLevel = 0) = 0;
  virtual void copyBufferToTexture(BufferId src, TextureId dst, uint64_t srcOffset = 0, uint32_t mipLevel = 0) = 0;
  virtual void fillBuffer(BufferId buffer, uint64_t offset, uint64_t size, uint32_t value) = 0;
  // Whole texture (every mip and layer) in the transfer-destination layout (Access::TransferDst).
  // Vulkan clears images only on graphics or compute queues: declare the node graphics or compute
  // (depth formats: graphics), never transfer.
  virtual void clearTexture(TextureId texture, const std::array<float, 4>& color) = 0;
};

}  // namespace fgb::rhi
