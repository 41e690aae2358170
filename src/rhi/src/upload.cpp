#include <fgb/rhi/job_context.hpp>
#include <fgb/rhi/upload.hpp>

#include <cstring>
#include <stdexcept>

namespace fgb::rhi {
namespace {

BufferId stagingWith(Device& device, std::span<const std::byte> bytes) {
  const BufferId staging = device.createBuffer({"upload staging", bytes.size(), kBufferTransferSrc, MemoryUsage::Upload});
  const auto mapped = device.mapped(staging);
  if (mapped.size() < bytes.size()) throw std::runtime_error("upload staging buffer is not host-visible");
  std::memcpy(mapped.data(), bytes.data(), bytes.size());
  return staging;
}

constexpr graph::ImportState kUntouched{graph::kStageNone, graph::kAccessNone, graph::Layout::Undefined};
constexpr graph::ImportState kHostWritten{graph::kStageHost, graph::kAccessHostWrite, graph::Layout::Undefined};

}  // namespace

void uploadBuffer(Device& device, BufferId dst, std::span<const std::byte> bytes) {
  if (bytes.empty()) return;
  const BufferId staging = stagingWith(device, bytes);
  graph::FrameGraph graph;
  const graph::ImportState after{graph::kStageAllCommands, graph::kAccessShaderStorageRead | graph::kAccessVertexAttributeRead |
                                                               graph::kAccessIndexRead | graph::kAccessIndirectCommandRead |
                                                               graph::kAccessUniformRead,
                                 graph::Layout::Undefined};
  const auto src = graph.importBuffer("staging", {bytes.size()}, external(staging), kHostWritten, kHostWritten);
  auto target = graph.importBuffer("upload target", {bytes.size()}, external(dst), kUntouched, after);
  // On the graphics queue: buffers are shared by every queue family, so no queue needs to own it.
  auto node = graph.addNode("Upload buffer", graph::NodeType::Transfer, graph::QueueClass::Graphics);
  node.read(src, graph::Access::TransferSrc);
  target = node.write(target, graph::Access::TransferDst);
  const uint64_t size = bytes.size();
  node.setJob([src, target, size](graph::JobContext& context) {
    auto& rhi = rhiContext(context);
    rhi.cmd().copyBuffer(rhi.buffer(src), rhi.buffer(target), size);
  });
  auto executable = device.compile(std::move(graph), {.name = "upload", .queues = 1, .timestamps = false});
  device.wait(device.execute(*executable));
  device.destroyBuffer(staging);
}

void uploadTexture(Device& device, TextureId dst, const TextureDesc& desc, std::span<const std::byte> texels) {
  if (texels.empty()) return;
  const BufferId staging = stagingWith(device, texels);
  graph::FrameGraph graph;
  const graph::ImportState after{graph::kStageAllCommands, graph::kAccessShaderSampledRead, graph::Layout::ShaderReadOnly};
  const auto src = graph.importBuffer("staging", {texels.size()}, external(staging), kHostWritten, kHostWritten);
  auto target = graph.importTexture("upload target", {desc.format, desc.extent, desc.mipLevels, desc.layers, desc.samples},
                                    external(dst), kUntouched, after);
  auto node = graph.addNode("Upload texture", graph::NodeType::Transfer);
  node.read(src, graph::Access::TransferSrc);
  target = node.write(target, graph::Access::TransferDst);
  node.setJob([src, target](graph::JobContext& context) {
    auto& rhi = rhiContext(context);
    rhi.cmd().copyBufferToTexture(rhi.buffer(src), rhi.texture(target));
  });
  auto executable = device.compile(std::move(graph), {.name = "upload", .queues = 1, .timestamps = false});
  device.wait(device.execute(*executable));
  device.destroyBuffer(staging);
}

}  // namespace fgb::rhi
