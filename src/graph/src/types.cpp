#include <fgb/graph/types.hpp>

#include "access_table.hpp"

namespace fgb::graph {

AccessInfo accessInfo(Access access, NodeType nodeType, StageMask shaderStages) {
  return detail::lookupAccessInfo(access, nodeType, shaderStages);
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

std::string_view toString(Layout layout) {
  switch (layout) {
    case Layout::Undefined: return "UNDEFINED";
    case Layout::General: return "GENERAL";
    case Layout::ColorAttachment: return "COLOR_ATTACHMENT";
    case Layout::DepthStencilAttachment: return "DEPTH_STENCIL_ATTACHMENT";
    case Layout::DepthStencilReadOnly: return "DEPTH_STENCIL_READ_ONLY";
    case Layout::ShaderReadOnly: return "SHADER_READ_ONLY";
    case Layout::TransferSrc: return "TRANSFER_SRC";
    case Layout::TransferDst: return "TRANSFER_DST";
  }
  return "?";
}

}  // namespace fgb::graph
