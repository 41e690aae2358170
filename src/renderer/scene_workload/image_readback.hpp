// Reads the frame's HDR and display images back to the host through a small side-effect graph.
#pragma once

#include <fgb/renderer/workload.hpp>
#include <fgb/rhi/device.hpp>
#include <memory>
#include <span>

namespace fgb::render {

// Tightly packed texels of `format` as linear float RGBA: half/float colour, one-channel floats and
// depth (replicated into RGB), and 8-bit display images (sRGB-encoded bytes, decoded). DeviceError
// for other formats.
ImageRGBA32F decodeTexels(graph::Format format, graph::Extent extent, std::span<const std::byte> bytes);

class ImageReadback {
 public:
  // `finalState` is the state the frame graph leaves `texture` in (imported on both sides).
  ImageReadback(rhi::Device& device, rhi::TextureId texture, graph::Format format, graph::Extent extent,
                graph::ImportState finalState);
  // Waits for all GPU work, copies the image and converts it to linear float RGBA.
  ImageRGBA32F read();

 private:
  rhi::Device& device_;
  graph::Format format_;
  graph::Extent extent_;
  rhi::BufferId buffer_;
  std::unique_ptr<rhi::ExecutableGraph> graph_;
};

}  // namespace fgb::render
