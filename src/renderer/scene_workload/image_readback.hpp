// Reads the frame's HDR and display images back to the host through a small side-effect graph.
#pragma once

#include <fgb/renderer/workload.hpp>
#include <fgb/rhi/device.hpp>

#include <memory>

namespace fgb::render {

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
