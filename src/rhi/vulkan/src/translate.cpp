#include "translate.hpp"

#include <fgb/core/error.hpp>

#include <string>

namespace fgb::vulkan {

VkFormat toVk(graph::Format format) {
  using graph::Format;
  switch (format) {
    case Format::Undefined: return VK_FORMAT_UNDEFINED;
    case Format::R8G8B8A8Unorm: return VK_FORMAT_R8G8B8A8_UNORM;
    case Format::R8G8B8A8Srgb: return VK_FORMAT_R8G8B8A8_SRGB;
    case Format::B8G8R8A8Unorm: return VK_FORMAT_B8G8R8A8_UNORM;
    case Format::R16G16B16A16Sfloat: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::R32G32B32A32Sfloat: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::B10G11R11UfloatPack32: return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
    case Format::R16G16Sfloat: return VK_FORMAT_R16G16_SFLOAT;
    case Format::R32Sfloat: return VK_FORMAT_R32_SFLOAT;
    case Format::R32Uint: return VK_FORMAT_R32_UINT;
    case Format::D32Sfloat: return VK_FORMAT_D32_SFLOAT;
    case Format::D24UnormS8Uint: return VK_FORMAT_D24_UNORM_S8_UINT;
    case Format::R64Uint: return VK_FORMAT_R64_UINT;
  }
  return VK_FORMAT_UNDEFINED;
}

VkFormat toVk(rhi::VertexFormat format) {
  using rhi::VertexFormat;
  switch (format) {
    case VertexFormat::R32Sfloat: return VK_FORMAT_R32_SFLOAT;
    case VertexFormat::R32G32Sfloat: return VK_FORMAT_R32G32_SFLOAT;
    case VertexFormat::R32G32B32Sfloat: return VK_FORMAT_R32G32B32_SFLOAT;
    case VertexFormat::R32G32B32A32Sfloat: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case VertexFormat::R8G8B8A8Unorm: return VK_FORMAT_R8G8B8A8_UNORM;
    case VertexFormat::R32Uint: return VK_FORMAT_R32_UINT;
  }
  return VK_FORMAT_UNDEFINED;
}

VkImageAspectFlags aspectOf(graph::Format format) {
  if (!graph::isDepthFormat(format)) return VK_IMAGE_ASPECT_COLOR_BIT;
  return graph::hasStencil(format) ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT : VK_IMAGE_ASPECT_DEPTH_BIT;
}

VkSampleCountFlagBits toVkSamples(uint32_t samples) {
  switch (samples) {
    case 1: return VK_SAMPLE_COUNT_1_BIT;
    case 2: return VK_SAMPLE_COUNT_2_BIT;
    case 4: return VK_SAMPLE_COUNT_4_BIT;
    case 8: return VK_SAMPLE_COUNT_8_BIT;
    case 16: return VK_SAMPLE_COUNT_16_BIT;
    default: throw InputError("sample count " + std::to_string(samples) + " is not 1, 2, 4, 8 or 16");
  }
}

VkPipelineStageFlags2 toVkStages(graph::StageMask stages) {
  struct Pair { graph::StageMask ours; VkPipelineStageFlags2 vk; };
  static constexpr Pair kPairs[] = {
      {graph::kStageDrawIndirect, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT},
      {graph::kStageVertexInput, VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT},
      {graph::kStageVertexShader, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT},
      {graph::kStageFragmentShader, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT},
      {graph::kStageEarlyFragmentTests, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT},
      {graph::kStageLateFragmentTests, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT},
      {graph::kStageColorAttachmentOutput, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT},
      {graph::kStageComputeShader, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT},
      {graph::kStageTransfer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT},
      // Dynamic-rendering resolves happen in the colour-attachment-output stage.
      {graph::kStageResolve, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT},
      {graph::kStageHost, VK_PIPELINE_STAGE_2_HOST_BIT},
      {graph::kStageAllCommands, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT},
      {graph::kStageTaskShader, VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT},
      {graph::kStageMeshShader, VK_PIPELINE_STAGE_2_MESH_SHADER_BIT_EXT},
  };
  VkPipelineStageFlags2 result = VK_PIPELINE_STAGE_2_NONE;
  for (const auto& pair : kPairs) {
    if (stages & pair.ours) result |= pair.vk;
  }
  return result;
}

VkAccessFlags2 toVkAccess(graph::AccessMask access) {
  struct Pair { graph::AccessMask ours; VkAccessFlags2 vk; };
  static constexpr Pair kPairs[] = {
      {graph::kAccessIndirectCommandRead, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT},
      {graph::kAccessIndexRead, VK_ACCESS_2_INDEX_READ_BIT},
      {graph::kAccessVertexAttributeRead, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT},
      {graph::kAccessUniformRead, VK_ACCESS_2_UNIFORM_READ_BIT},
      {graph::kAccessShaderSampledRead, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT},
      {graph::kAccessShaderStorageRead, VK_ACCESS_2_SHADER_STORAGE_READ_BIT},
      {graph::kAccessShaderStorageWrite, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT},
      {graph::kAccessColorAttachmentRead, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT},
      {graph::kAccessColorAttachmentWrite, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
      {graph::kAccessDepthStencilRead, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT},
      {graph::kAccessDepthStencilWrite, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT},
      {graph::kAccessTransferRead, VK_ACCESS_2_TRANSFER_READ_BIT},
      {graph::kAccessTransferWrite, VK_ACCESS_2_TRANSFER_WRITE_BIT},
      {graph::kAccessHostRead, VK_ACCESS_2_HOST_READ_BIT},
      {graph::kAccessHostWrite, VK_ACCESS_2_HOST_WRITE_BIT},
  };
  VkAccessFlags2 result = VK_ACCESS_2_NONE;
  for (const auto& pair : kPairs) {
    if (access & pair.ours) result |= pair.vk;
  }
  return result;
}

VkAccessFlags2 supportedAccess(VkQueueFlags family) {
  VkAccessFlags2 access = VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT |
                          VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  if (family & (VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT)) {
    access |= VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_UNIFORM_READ_BIT |
              VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
              VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  }
  if (family & VK_QUEUE_GRAPHICS_BIT) {
    access |= VK_ACCESS_2_INDEX_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT |
              VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  }
  return access;
}

VkImageLayout toVk(graph::Layout layout) {
  using graph::Layout;
  switch (layout) {
    case Layout::Undefined: return VK_IMAGE_LAYOUT_UNDEFINED;
    case Layout::General: return VK_IMAGE_LAYOUT_GENERAL;
    case Layout::ColorAttachment: return VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    case Layout::DepthStencilAttachment: return VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    case Layout::DepthStencilReadOnly: return VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    case Layout::ShaderReadOnly: return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    case Layout::TransferSrc: return VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    case Layout::TransferDst: return VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  }
  return VK_IMAGE_LAYOUT_UNDEFINED;
}

VkBufferUsageFlags toVkBufferUsage(rhi::BufferUsage usage) {
  VkBufferUsageFlags flags = 0;
  if (usage & rhi::kBufferVertex) flags |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  if (usage & rhi::kBufferIndex) flags |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
  if (usage & rhi::kBufferStorage) flags |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (usage & rhi::kBufferUniform) flags |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  if (usage & rhi::kBufferIndirect) flags |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  if (usage & rhi::kBufferTransferSrc) flags |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  if (usage & rhi::kBufferTransferDst) flags |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  return flags;
}

VkImageUsageFlags toVkImageUsage(rhi::TextureUsage usage, graph::Format format) {
  VkImageUsageFlags flags = 0;
  if (usage & rhi::kTextureSampled) flags |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (usage & rhi::kTextureStorage) flags |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (usage & rhi::kTextureColorAttachment) flags |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (usage & rhi::kTextureDepthAttachment) flags |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  if (usage & rhi::kTextureTransferSrc) flags |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (usage & rhi::kTextureTransferDst) flags |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  // A resolve target is written as a colour attachment; depth formats cannot be.
  if (graph::isDepthFormat(format)) flags &= ~VkImageUsageFlags{VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT};
  return flags;
}

rhi::BufferUsage bufferUsageFor(graph::Access access) {
  using graph::Access;
  switch (access) {
    case Access::Sampled:
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite:
    case Access::StorageSampledWrite: return rhi::kBufferStorage;
    case Access::TransferSrc: return rhi::kBufferTransferSrc;
    case Access::TransferDst: return rhi::kBufferTransferDst;
    case Access::Indirect: return rhi::kBufferIndirect;
    case Access::Vertex: return rhi::kBufferVertex;
    case Access::Index: return rhi::kBufferIndex;
    case Access::Uniform: return rhi::kBufferUniform;
    default: return 0;
  }
}

rhi::TextureUsage textureUsageFor(graph::Access access) {
  using graph::Access;
  switch (access) {
    case Access::Sampled: return rhi::kTextureSampled;
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite: return rhi::kTextureStorage;
    case Access::StorageSampledWrite: return rhi::kTextureStorage | rhi::kTextureSampled;
    case Access::ColorAttachmentWrite:
    case Access::ColorAttachmentReadWrite:
    case Access::ResolveDst: return rhi::kTextureColorAttachment;
    case Access::DepthAttachmentWrite:
    case Access::DepthAttachmentReadWrite:
    case Access::DepthAttachmentRead: return rhi::kTextureDepthAttachment;
    case Access::TransferSrc: return rhi::kTextureTransferSrc;
    case Access::TransferDst: return rhi::kTextureTransferDst;
    default: return 0;
  }
}

VkCompareOp toVk(rhi::CompareOp op) {
  // The RHI enum follows VkCompareOp's order.
  return static_cast<VkCompareOp>(static_cast<int>(op));
}

VkPrimitiveTopology toVk(rhi::Topology topology) {
  switch (topology) {
    case rhi::Topology::TriangleList: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    case rhi::Topology::TriangleStrip: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    case rhi::Topology::LineList: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    case rhi::Topology::PointList: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
  }
  return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
}

VkCullModeFlags toVk(rhi::CullMode mode) {
  switch (mode) {
    case rhi::CullMode::None: return VK_CULL_MODE_NONE;
    case rhi::CullMode::Back: return VK_CULL_MODE_BACK_BIT;
    case rhi::CullMode::Front: return VK_CULL_MODE_FRONT_BIT;
  }
  return VK_CULL_MODE_NONE;
}

VkFilter toVk(rhi::Filter filter) { return filter == rhi::Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST; }

VkSamplerMipmapMode toVkMipmap(rhi::Filter filter) {
  return filter == rhi::Filter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
}

VkSamplerAddressMode toVk(rhi::AddressMode mode) {
  switch (mode) {
    case rhi::AddressMode::Repeat: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    case rhi::AddressMode::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    case rhi::AddressMode::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  }
  return VK_SAMPLER_ADDRESS_MODE_REPEAT;
}

VkAttachmentLoadOp toVk(graph::LoadOp op) {
  switch (op) {
    case graph::LoadOp::Load: return VK_ATTACHMENT_LOAD_OP_LOAD;
    case graph::LoadOp::Clear: return VK_ATTACHMENT_LOAD_OP_CLEAR;
    case graph::LoadOp::DontCare: return VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  }
  return VK_ATTACHMENT_LOAD_OP_LOAD;
}

VkAttachmentStoreOp toVk(graph::StoreOp op) {
  return op == graph::StoreOp::Store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
}

}  // namespace fgb::vulkan
