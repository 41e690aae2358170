// Internal: accessInfo() as an inline table lookup. Declaration looks it up for every use, so it
// should cost a load, not a call through a switch.
#pragma once

#include <fgb/graph/types.hpp>

#include <array>
#include <cstddef>

namespace fgb::graph::detail {

// One row per Access; stages kStageNone means "the shader stages of the node type".
inline constexpr std::array<AccessInfo, 17> kAccessTable = [] {
  constexpr StageMask kShader = kStageNone;
  constexpr StageMask kDepthStages = kStageEarlyFragmentTests | kStageLateFragmentTests;
  std::array<AccessInfo, 17> table{};
  auto row = [&table](Access access, AccessInfo info) { table[static_cast<size_t>(access)] = info; };
  row(Access::Sampled, {true, false, kShader, kAccessShaderSampledRead, Layout::ShaderReadOnly});
  row(Access::StorageRead, {true, false, kShader, kAccessShaderStorageRead, Layout::General});
  row(Access::StorageWrite, {false, true, kShader, kAccessShaderStorageWrite, Layout::General});
  row(Access::StorageReadWrite,
      {true, true, kShader, kAccessShaderStorageRead | kAccessShaderStorageWrite, Layout::General});
  row(Access::ColorAttachmentWrite,
      {false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite, Layout::ColorAttachment});
  row(Access::ColorAttachmentReadWrite, {true, true, kStageColorAttachmentOutput,
                                         kAccessColorAttachmentRead | kAccessColorAttachmentWrite,
                                         Layout::ColorAttachment});
  row(Access::DepthAttachmentWrite,
      {false, true, kDepthStages, kAccessDepthStencilWrite, Layout::DepthStencilAttachment});
  row(Access::DepthAttachmentReadWrite, {true, true, kDepthStages,
                                         kAccessDepthStencilRead | kAccessDepthStencilWrite,
                                         Layout::DepthStencilAttachment});
  row(Access::DepthAttachmentRead,
      {true, false, kDepthStages, kAccessDepthStencilRead, Layout::DepthStencilReadOnly});
  // Dynamic-rendering resolves run in the colour-attachment-output stage.
  row(Access::ResolveDst,
      {false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite, Layout::ColorAttachment});
  row(Access::TransferSrc, {true, false, kStageTransfer, kAccessTransferRead, Layout::TransferSrc});
  row(Access::TransferDst, {false, true, kStageTransfer, kAccessTransferWrite, Layout::TransferDst});
  row(Access::Indirect, {true, false, kStageDrawIndirect, kAccessIndirectCommandRead, Layout::General});
  row(Access::Vertex, {true, false, kStageVertexInput, kAccessVertexAttributeRead, Layout::General});
  row(Access::Index, {true, false, kStageVertexInput, kAccessIndexRead, Layout::General});
  row(Access::Uniform, {true, false, kShader, kAccessUniformRead, Layout::General});
  row(Access::HostRead, {true, false, kStageHost, kAccessHostRead, Layout::General});
  return table;
}();

// The shader stages of each node type, by NodeType value.
inline constexpr std::array<StageMask, 3> kShaderStagesOfType = {
    kStageVertexShader | kStageFragmentShader,  // Graphics
    kStageComputeShader,                        // Compute
    kStageTransfer,                             // Transfer
};

inline StageMask shaderStagesOf(NodeType type) {
  const auto index = static_cast<size_t>(type);
  return index < kShaderStagesOfType.size() ? kShaderStagesOfType[index] : kStageAllCommands;
}

// `value` where `mask` is all ones, `otherwise` where it is zero.
inline StageMask selectStages(StageMask mask, StageMask value, StageMask otherwise) {
  return (value & mask) | (otherwise & ~mask);
}

// Without branches on what the row or the node type is: node types and accesses of consecutive
// uses follow no pattern a predictor can learn.
inline AccessInfo lookupAccessInfo(Access access, NodeType nodeType, StageMask shaderStages) {
  const auto row = static_cast<size_t>(access);
  if (row >= kAccessTable.size()) return {true, true, kStageAllCommands, kAccessNone, Layout::General};
  AccessInfo info = kAccessTable[row];
  const StageMask declared = 0u - static_cast<StageMask>(shaderStages != kStageNone);  // all ones if given
  const StageMask shader = selectStages(declared, shaderStages, shaderStagesOf(nodeType));
  info.stages = selectStages(0u - static_cast<StageMask>(info.stages == kStageNone), shader, info.stages);
  return info;
}

}  // namespace fgb::graph::detail
