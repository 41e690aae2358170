// The context a node's job receives (graph::Job takes graph::JobContext&; the backend passes one
// of these). It resolves the graph handles the node declared to physical RHI objects and their
// bindless descriptor indices.
#pragma once

#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/command_buffer.hpp>
#include <fgb/rhi/types.hpp>

#include <cstdint>

namespace fgb::rhi {

class JobContext : public graph::JobContext {
 public:
  virtual CommandBuffer& cmd() = 0;
  [[nodiscard]] virtual BufferId buffer(graph::BufferHandle handle) const = 0;
  [[nodiscard]] virtual TextureId texture(graph::TextureHandle handle) const = 0;
  // Indices into the shared descriptor set (see shaders/include/bindless.glsl).
  [[nodiscard]] virtual uint32_t storageBufferIndex(graph::BufferHandle handle) const = 0;
  [[nodiscard]] virtual uint32_t sampledTextureIndex(graph::TextureHandle handle) const = 0;
  [[nodiscard]] virtual uint32_t storageTextureIndex(graph::TextureHandle handle) const = 0;
  // A sampled-texture index whose descriptor is in the GENERAL layout, for a texture the node
  // declared graph::Access::StorageSampledWrite: the node may sample it (after its own barrier)
  // between dispatches that write it as storage.
  [[nodiscard]] virtual uint32_t sampledGeneralTextureIndex(graph::TextureHandle handle) const = 0;
  // How many times this graph ran before (0 on the first execution).
  [[nodiscard]] virtual uint64_t execution() const = 0;
  // Extent of the node's attachments (graphics nodes), else 1x1.
  [[nodiscard]] virtual graph::Extent renderExtent() const = 0;
};

// The RHI context behind a graph::JobContext handed to a job by this backend.
inline JobContext& rhiContext(graph::JobContext& context) { return static_cast<JobContext&>(context); }

}  // namespace fgb::rhi
