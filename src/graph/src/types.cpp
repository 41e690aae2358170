#include <fgb/graph/types.hpp>
#include <iterator>

namespace fgb::graph {
namespace {

// Each enum below is one table, a row per value in the enum's order (sizes checked by
// static_assert): a value's name and what it implies are listed once, side by side. `fallback` is
// for a value past the table, which only a cast from a bad integer makes.
template <typename Row, size_t N, typename Enum>
constexpr const Row& rowOf(const Row (&rows)[N], Enum value, const Row& fallback) {
  const auto index = static_cast<size_t>(value);
  return index < N ? rows[index] : fallback;
}

struct AccessRow {
  std::string_view name;
  AccessInfo info;
};

// Stages kStageNone stand for the shader stages of the node's type (or those the use declares).
constexpr StageMask kShader = kStageNone;
constexpr StageMask kDepth = kStageEarlyFragmentTests | kStageLateFragmentTests;
constexpr AccessMask kStorageReadWrite = kAccessShaderStorageRead | kAccessShaderStorageWrite;
constexpr AccessMask kColorReadWrite = kAccessColorAttachmentRead | kAccessColorAttachmentWrite;
constexpr AccessMask kDepthReadWrite = kAccessDepthStencilRead | kAccessDepthStencilWrite;

constexpr AccessRow kAccessRows[] = {
    {"sampled", {true, false, kShader, kAccessShaderSampledRead, Layout::ShaderReadOnly}},
    {"storage-read", {true, false, kShader, kAccessShaderStorageRead, Layout::General}},
    {"storage-write", {false, true, kShader, kAccessShaderStorageWrite, Layout::General}},
    {"storage-read-write", {true, true, kShader, kStorageReadWrite, Layout::General}},
    {"color-write", {false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite, Layout::ColorAttachment}},
    {"color-read-write", {true, true, kStageColorAttachmentOutput, kColorReadWrite, Layout::ColorAttachment}},
    {"depth-write", {false, true, kDepth, kAccessDepthStencilWrite, Layout::DepthStencilAttachment}},
    {"depth-read-write", {true, true, kDepth, kDepthReadWrite, Layout::DepthStencilAttachment}},
    {"depth-read", {true, false, kDepth, kAccessDepthStencilRead, Layout::DepthStencilReadOnly}},
    // Dynamic-rendering resolves run in the colour-attachment-output stage.
    {"resolve", {false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite, Layout::ColorAttachment}},
    {"transfer-src", {true, false, kStageTransfer, kAccessTransferRead, Layout::TransferSrc}},
    {"transfer-dst", {false, true, kStageTransfer, kAccessTransferWrite, Layout::TransferDst}},
    {"indirect", {true, false, kStageDrawIndirect, kAccessIndirectCommandRead, Layout::General}},
    {"vertex", {true, false, kStageVertexInput, kAccessVertexAttributeRead, Layout::General}},
    {"index", {true, false, kStageVertexInput, kAccessIndexRead, Layout::General}},
    {"uniform", {true, false, kShader, kAccessUniformRead, Layout::General}},
    {"host-read", {true, false, kStageHost, kAccessHostRead, Layout::General}},
    // The sampled read is the node's own (after its own barrier) but still in its access mask, so
    // the barrier into the node makes earlier writes (or the layout transition) visible to it too.
    {"storage-sampled-write",
     {false, true, kShader, kAccessShaderStorageWrite | kAccessShaderSampledRead, Layout::General}},
};
static_assert(std::size(kAccessRows) == static_cast<size_t>(kLastAccess) + 1);
// An unknown access: assume it does everything.
constexpr AccessRow kUnknownAccess{"?", {true, true, kStageAllCommands, kAccessNone, Layout::General}};

struct NodeTypeRow {
  std::string_view name;
  StageMask shaderStages;
  QueueClass defaultQueue;
};

constexpr NodeTypeRow kNodeTypeRows[] = {
    {"graphics", kStageVertexShader | kStageFragmentShader, QueueClass::Graphics},
    {"compute", kStageComputeShader, QueueClass::Compute},
    {"transfer", kStageTransfer, QueueClass::Transfer},
};
static_assert(std::size(kNodeTypeRows) == static_cast<size_t>(NodeType::Transfer) + 1);
constexpr NodeTypeRow kUnknownNodeType{"?", kStageAllCommands, QueueClass::Graphics};

constexpr std::string_view kQueueClassNames[] = {"graphics", "compute", "transfer"};
static_assert(std::size(kQueueClassNames) == kQueueClassCount);

}  // namespace

AccessInfo accessInfo(Access access, NodeType nodeType, StageMask shaderStages) {
  AccessInfo info = rowOf(kAccessRows, access, kUnknownAccess).info;
  const StageMask typeStages = rowOf(kNodeTypeRows, nodeType, kUnknownNodeType).shaderStages;
  if (info.stages == kShader) info.stages = shaderStages != kStageNone ? shaderStages : typeStages;
  return info;
}

bool isWriteAccess(Access access) {
  return rowOf(kAccessRows, access, kUnknownAccess).info.writes;
}

QueueClass defaultQueue(NodeType type) {
  return rowOf(kNodeTypeRows, type, kUnknownNodeType).defaultQueue;
}

std::string_view toString(Access access) {
  return rowOf(kAccessRows, access, kUnknownAccess).name;
}

std::string_view toString(NodeType type) {
  return rowOf(kNodeTypeRows, type, kUnknownNodeType).name;
}

std::string_view toString(QueueClass queue) {
  static constexpr std::string_view kUnknown = "?";
  return rowOf(kQueueClassNames, queue, kUnknown);
}

}  // namespace fgb::graph
