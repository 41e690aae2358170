// Resource and pipeline descriptions of the RHI. API-agnostic: the Vulkan backend maps them.
// Objects are named by small typed ids into the device's tables; they live as long as the Device.
#pragma once

#include <fgb/graph/format.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/shared/bindless.h>

#include <cstdint>
#include <string>
#include <vector>

namespace fgb::rhi {

inline constexpr uint32_t kInvalidId = graph::kInvalidIndex;
static_assert(kInvalidId == FGB_NONE, "shaders test indices against FGB_NONE");

// Typed ids keep a buffer from being passed where a texture is expected.
template <class Tag>
struct Id {
  uint32_t index = kInvalidId;
  [[nodiscard]] bool valid() const { return index != kInvalidId; }
  friend bool operator==(Id, Id) = default;
};
using BufferId = Id<struct BufferTag>;
using TextureId = Id<struct TextureTag>;
using SamplerId = Id<struct SamplerTag>;
using PipelineId = Id<struct PipelineTag>;

// Where a resource's memory lives. Host-visible buffers stay mapped for their whole life.
enum class MemoryUsage : uint8_t {
  DeviceLocal,  // GPU only
  Upload,       // host writes, GPU reads (staging)
  Readback,     // GPU writes, host reads
};

enum BufferUsageBits : uint32_t {
  kBufferVertex = 1u << 0,
  kBufferIndex = 1u << 1,
  kBufferStorage = 1u << 2,
  kBufferUniform = 1u << 3,
  kBufferIndirect = 1u << 4,
  kBufferTransferSrc = 1u << 5,
  kBufferTransferDst = 1u << 6,
};
using BufferUsage = uint32_t;

enum TextureUsageBits : uint32_t {
  kTextureSampled = 1u << 0,
  kTextureStorage = 1u << 1,
  kTextureColorAttachment = 1u << 2,
  kTextureDepthAttachment = 1u << 3,
  kTextureTransferSrc = 1u << 4,
  kTextureTransferDst = 1u << 5,
};
using TextureUsage = uint32_t;

struct BufferDesc {
  std::string name{};
  uint64_t size = 0;
  BufferUsage usage = 0;
  MemoryUsage memory = MemoryUsage::DeviceLocal;
};

struct TextureDesc {
  std::string name{};
  graph::Format format = graph::Format::Undefined;
  graph::Extent extent{};
  uint32_t mipLevels = 1;
  uint32_t layers = 1;
  uint32_t samples = 1;
  TextureUsage usage = 0;
};

enum class Filter : uint8_t { Nearest, Linear };
enum class AddressMode : uint8_t { Repeat, MirroredRepeat, ClampToEdge };

struct SamplerDesc {
  std::string name{};
  Filter magFilter = Filter::Linear;
  Filter minFilter = Filter::Linear;
  Filter mipFilter = Filter::Linear;
  AddressMode addressMode = AddressMode::Repeat;
  float maxAnisotropy = 1.0f;  // > 1 enables anisotropic filtering where the device has it
};

enum class VertexFormat : uint8_t { R32Sfloat, R32G32Sfloat, R32G32B32Sfloat, R32G32B32A32Sfloat, R8G8B8A8Unorm, R32Uint };

struct VertexBinding {
  uint32_t binding = 0;
  uint32_t stride = 0;
  bool perInstance = false;
};

struct VertexAttribute {
  uint32_t location = 0;
  uint32_t binding = 0;
  VertexFormat format = VertexFormat::R32G32B32A32Sfloat;
  uint32_t offset = 0;
};

enum class Topology : uint8_t { TriangleList, TriangleStrip, LineList, PointList };
enum class CullMode : uint8_t { None, Back, Front };
enum class CompareOp : uint8_t { Never, Less, Equal, LessOrEqual, Greater, NotEqual, GreaterOrEqual, Always };
enum class BlendMode : uint8_t { Opaque, Alpha, Additive };
enum class IndexType : uint8_t { Uint16, Uint32 };

// Graphics pipelines render with dynamic rendering into the formats listed here; viewport and
// scissor are dynamic (the executor sets them to the attachments' extent before the job runs).
// A mesh pipeline (Device::meshShaders()) names meshShader (and optionally taskShader) instead of
// vertexShader; it has no vertex input or topology (the mesh shader emits triangles) and is drawn
// with CommandBuffer::drawMeshTasks*.
struct GraphicsPipelineDesc {
  std::string name{};
  std::string vertexShader{};    // path under shaders/, e.g. "proof/scene.vert"
  std::string fragmentShader{};  // empty: depth-only
  std::string taskShader{};      // mesh pipelines: optional, e.g. "renderer/meshlets/meshlet.task"
  std::string meshShader{};      // non-empty: a mesh pipeline (vertexShader, vertex input unused)
  std::vector<VertexBinding> vertexBindings{};
  std::vector<VertexAttribute> vertexAttributes{};
  Topology topology = Topology::TriangleList;
  CullMode cullMode = CullMode::None;
  bool frontFaceCounterClockwise = true;
  std::vector<graph::Format> colorFormats{};
  std::vector<BlendMode> blend{};  // per colour attachment; missing entries are Opaque
  graph::Format depthFormat = graph::Format::Undefined;
  bool depthTest = false;
  bool depthWrite = false;
  CompareOp depthCompare = CompareOp::GreaterOrEqual;  // reversed-Z friendly default
  uint32_t samples = 1;
};

struct ComputePipelineDesc {
  std::string name{};
  std::string shader{};  // path under shaders/, e.g. "proof/pattern.comp"
};

// Every pipeline shares one layout: the bindless set plus this many bytes of push constants.
inline constexpr uint32_t kPushConstantBytes = FGB_PUSH_CONSTANT_BYTES;

// Imported graph resources refer to RHI objects through ExternalResource ids.
graph::ExternalResource external(BufferId buffer);
graph::ExternalResource external(TextureId texture);
// The RHI object an ExternalResource names; an invalid id when it names the other kind.
BufferId externalBuffer(graph::ExternalResource resource);
TextureId externalTexture(graph::ExternalResource resource);

}  // namespace fgb::rhi
