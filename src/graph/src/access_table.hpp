// Internal: accessInfo() as an inline table lookup. Declaration looks it up for every use, so it
// should cost a load, not a call through a switch (nor selects on the node type).
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

inline bool isKnownAccess(Access access) { return static_cast<size_t>(access) < kAccessTable.size(); }

// kAccessTable with the stages of each row resolved for each node type (by NodeType value), and
// whether the row's stages are the node's shader stages (which stages a use declares replace).
struct UseRow {
  AccessInfo info;
  bool shaderStages;
};
inline constexpr std::array<std::array<UseRow, kShaderStagesOfType.size()>, kAccessTable.size()> kUseTable = [] {
  std::array<std::array<UseRow, kShaderStagesOfType.size()>, kAccessTable.size()> table{};
  for (size_t access = 0; access < kAccessTable.size(); ++access) {
    for (size_t type = 0; type < kShaderStagesOfType.size(); ++type) {
      UseRow& row = table[access][type];
      row.info = kAccessTable[access];
      row.shaderStages = row.info.stages == kStageNone;
      if (row.shaderStages) row.info.stages = kShaderStagesOfType[type];
    }
  }
  return table;
}();

// What a use of a known access (isKnownAccess) by a known node type records (FrameGraph checks both).
// Uses rarely declare their own shader stages: a branch on it is predicted.
inline AccessInfo lookupUse(Access access, NodeType nodeType, StageMask shaderStages) {
  const UseRow& row = kUseTable[static_cast<size_t>(access)][static_cast<size_t>(nodeType)];
  AccessInfo info = row.info;
  if (shaderStages != kStageNone && row.shaderStages) info.stages = shaderStages;
  return info;
}

// accessInfo(): lookupUse() for any access and node type (unknown ones get every stage).
inline AccessInfo lookupAccessInfo(Access access, NodeType nodeType, StageMask shaderStages) {
  if (!isKnownAccess(access)) return {true, true, kStageAllCommands, kAccessNone, Layout::General};
  if (static_cast<size_t>(nodeType) < kShaderStagesOfType.size()) return lookupUse(access, nodeType, shaderStages);
  AccessInfo info = kAccessTable[static_cast<size_t>(access)];
  if (info.stages == kStageNone) info.stages = shaderStages != kStageNone ? shaderStages : kStageAllCommands;
  return info;
}

}  // namespace fgb::graph::detail
