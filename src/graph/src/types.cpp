#include <fgb/graph/types.hpp>

namespace fgb::graph {
namespace {

// What each access does. Stages kStageNone stand for the shader stages of the node's type (or
// those the use declares).
AccessInfo accessRow(Access access) {
  constexpr StageMask kShader = kStageNone;
  constexpr StageMask kDepth = kStageEarlyFragmentTests | kStageLateFragmentTests;
  constexpr AccessMask kColorReadWrite = kAccessColorAttachmentRead | kAccessColorAttachmentWrite;
  constexpr AccessMask kDepthReadWrite = kAccessDepthStencilRead | kAccessDepthStencilWrite;
  switch (access) {
    case Access::Sampled: return {true, false, kShader, kAccessShaderSampledRead, Layout::ShaderReadOnly};
    case Access::StorageRead: return {true, false, kShader, kAccessShaderStorageRead, Layout::General};
    case Access::StorageWrite: return {false, true, kShader, kAccessShaderStorageWrite, Layout::General};
    case Access::StorageReadWrite:
      return {true, true, kShader, kAccessShaderStorageRead | kAccessShaderStorageWrite, Layout::General};
    case Access::ColorAttachmentWrite:
      return {false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite, Layout::ColorAttachment};
    case Access::ColorAttachmentReadWrite:
      return {true, true, kStageColorAttachmentOutput, kColorReadWrite, Layout::ColorAttachment};
    case Access::DepthAttachmentWrite:
      return {false, true, kDepth, kAccessDepthStencilWrite, Layout::DepthStencilAttachment};
    case Access::DepthAttachmentReadWrite: return {true, true, kDepth, kDepthReadWrite, Layout::DepthStencilAttachment};
    case Access::DepthAttachmentRead: return {true, false, kDepth, kAccessDepthStencilRead, Layout::DepthStencilReadOnly};
    // Dynamic-rendering resolves run in the colour-attachment-output stage.
    case Access::ResolveDst:
      return {false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite, Layout::ColorAttachment};
    case Access::TransferSrc: return {true, false, kStageTransfer, kAccessTransferRead, Layout::TransferSrc};
    case Access::TransferDst: return {false, true, kStageTransfer, kAccessTransferWrite, Layout::TransferDst};
    case Access::Indirect: return {true, false, kStageDrawIndirect, kAccessIndirectCommandRead, Layout::General};
    case Access::Vertex: return {true, false, kStageVertexInput, kAccessVertexAttributeRead, Layout::General};
    case Access::Index: return {true, false, kStageVertexInput, kAccessIndexRead, Layout::General};
    case Access::Uniform: return {true, false, kShader, kAccessUniformRead, Layout::General};
    case Access::HostRead: return {true, false, kStageHost, kAccessHostRead, Layout::General};
  }
  return {true, true, kStageAllCommands, kAccessNone, Layout::General};  // unknown: assume everything
}

StageMask shaderStagesOf(NodeType type) {
  switch (type) {
    case NodeType::Graphics: return kStageVertexShader | kStageFragmentShader;
    case NodeType::Compute: return kStageComputeShader;
    case NodeType::Transfer: return kStageTransfer;
  }
  return kStageAllCommands;
}

}  // namespace

AccessInfo accessInfo(Access access, NodeType nodeType, StageMask shaderStages) {
  AccessInfo info = accessRow(access);
  if (info.stages == kStageNone) info.stages = shaderStages != kStageNone ? shaderStages : shaderStagesOf(nodeType);
  return info;
}

bool isWriteAccess(Access access) { return accessRow(access).writes; }

QueueClass defaultQueue(NodeType type) {
  switch (type) {
    case NodeType::Graphics: return QueueClass::Graphics;
    case NodeType::Compute: return QueueClass::Compute;
    case NodeType::Transfer: return QueueClass::Transfer;
  }
  return QueueClass::Graphics;
}

std::string_view toString(Access access) {
  switch (access) {
    case Access::Sampled: return "sampled";
    case Access::StorageRead: return "storage-read";
    case Access::StorageWrite: return "storage-write";
    case Access::StorageReadWrite: return "storage-read-write";
    case Access::ColorAttachmentWrite: return "color-write";
    case Access::ColorAttachmentReadWrite: return "color-read-write";
    case Access::DepthAttachmentWrite: return "depth-write";
    case Access::DepthAttachmentReadWrite: return "depth-read-write";
    case Access::DepthAttachmentRead: return "depth-read";
    case Access::ResolveDst: return "resolve";
    case Access::TransferSrc: return "transfer-src";
    case Access::TransferDst: return "transfer-dst";
    case Access::Indirect: return "indirect";
    case Access::Vertex: return "vertex";
    case Access::Index: return "index";
    case Access::Uniform: return "uniform";
    case Access::HostRead: return "host-read";
  }
  return "?";
}

std::string_view toString(NodeType type) {
  switch (type) {
    case NodeType::Graphics: return "graphics";
    case NodeType::Compute: return "compute";
    case NodeType::Transfer: return "transfer";
  }
  return "?";
}

std::string_view toString(QueueClass queue) {
  switch (queue) {
    case QueueClass::Graphics: return "graphics";
    case QueueClass::Compute: return "compute";
    case QueueClass::Transfer: return "transfer";
  }
  return "?";
}

}  // namespace fgb::graph
