// Basic vocabulary of the frame graph: queues, node types, resource accesses and the abstract
// synchronisation state (stages, access masks, layouts). Follows Vulkan synchronization2 closely so
// the backend maps it 1:1, but contains no Vulkan types: the graph library stays API-agnostic.
#pragma once

#include <cstdint>
#include <limits>
#include <string_view>

namespace fgb::graph {

inline constexpr uint32_t kInvalidIndex = std::numeric_limits<uint32_t>::max();

enum class NodeType : uint8_t { Graphics, Compute, Transfer };
enum class QueueClass : uint8_t { Graphics, Compute, Transfer };
inline constexpr uint32_t kQueueClassCount = 3;

// Pipeline stages (bit values are ours; the backend translates them).
enum StageBits : uint32_t {
  kStageNone = 0,
  kStageDrawIndirect = 1u << 0,
  kStageVertexInput = 1u << 1,
  kStageVertexShader = 1u << 2,
  kStageFragmentShader = 1u << 3,
  kStageEarlyFragmentTests = 1u << 4,
  kStageLateFragmentTests = 1u << 5,
  kStageColorAttachmentOutput = 1u << 6,
  kStageComputeShader = 1u << 7,
  kStageTransfer = 1u << 8,
  kStageResolve = 1u << 9,  // dynamic-rendering resolve runs in ColorAttachmentOutput
  kStageHost = 1u << 10,
  kStageAllCommands = 1u << 11,
  kStageTaskShader = 1u << 12,  // mesh pipelines (VK_EXT_mesh_shader): only on devices that have them
  kStageMeshShader = 1u << 13,
};
using StageMask = uint32_t;

enum AccessBits : uint32_t {
  kAccessNone = 0,
  kAccessIndirectCommandRead = 1u << 0,
  kAccessIndexRead = 1u << 1,
  kAccessVertexAttributeRead = 1u << 2,
  kAccessUniformRead = 1u << 3,
  kAccessShaderSampledRead = 1u << 4,
  kAccessShaderStorageRead = 1u << 5,
  kAccessShaderStorageWrite = 1u << 6,
  kAccessColorAttachmentRead = 1u << 7,
  kAccessColorAttachmentWrite = 1u << 8,
  kAccessDepthStencilRead = 1u << 9,
  kAccessDepthStencilWrite = 1u << 10,
  kAccessTransferRead = 1u << 11,
  kAccessTransferWrite = 1u << 12,
  kAccessHostRead = 1u << 13,
  kAccessHostWrite = 1u << 14,
};
using AccessMask = uint32_t;
inline constexpr AccessMask kWriteAccesses = kAccessShaderStorageWrite | kAccessColorAttachmentWrite |
                                             kAccessDepthStencilWrite | kAccessTransferWrite | kAccessHostWrite;

enum class Layout : uint8_t {
  Undefined,
  General,
  ColorAttachment,
  DepthStencilAttachment,
  DepthStencilReadOnly,
  ShaderReadOnly,
  TransferSrc,
  TransferDst,
};

// How a node uses a resource. Every write produces a new version of the resource.
enum class Access : uint8_t {
  Sampled,                   // read: sampled image / texel fetch
  StorageRead,               // read: storage image or buffer
  StorageWrite,              // write: storage image or buffer, previous contents discarded
  StorageReadWrite,          // read + write: storage, previous contents kept
  ColorAttachmentWrite,      // write: colour target (clear or don't-care load)
  ColorAttachmentReadWrite,  // read + write: colour target with load, or blending onto it
  DepthAttachmentWrite,      // write: depth target (clear or don't-care load)
  DepthAttachmentReadWrite,  // read + write: depth test and write against earlier depth
  DepthAttachmentRead,       // read: depth test without depth writes
  ResolveDst,                // write: multisample resolve target
  TransferSrc,               // read: copy/blit source
  TransferDst,               // write: copy/blit/fill destination
  Indirect,                  // read: indirect draw/dispatch arguments (and count)
  Vertex,                    // read: vertex buffer
  Index,                     // read: index buffer
  Uniform,                   // read: uniform buffer
  HostRead,                  // read: mapped readback after the graph (side effect)
  // write: storage image, previous contents discarded, that the node also samples (a sampled
  // descriptor in the GENERAL layout) between its own barriers, e.g. a chain of levels each
  // dispatch writes and the next one filters. Last so that the values above keep their numbers.
  StorageSampledWrite,
};
inline constexpr Access kLastAccess = Access::StorageSampledWrite;

// Queue/node/resource state a use implies. Stages for shader accesses depend on the node type;
// StageMask 0 in a use means "derive from the node type".
struct AccessInfo {
  bool reads;
  bool writes;
  StageMask stages;
  AccessMask access;
  Layout layout;  // for textures; ignored for buffers
};
AccessInfo accessInfo(Access access, NodeType nodeType, StageMask shaderStages = kStageNone);

// accessInfo(access, ...).writes: whether the access produces a new version.
bool isWriteAccess(Access access);

std::string_view toString(Access access);
std::string_view toString(NodeType type);
std::string_view toString(QueueClass queue);

// The queue class a node of `type` runs on unless declared otherwise.
QueueClass defaultQueue(NodeType type);

}  // namespace fgb::graph
