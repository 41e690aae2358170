// --capture: the last frame's outputs of chosen nodes, read back for per-pass goldens (issue 29).
// Like --check-finite, it is declared last and reads the exact version each node wrote: for every
// captured node, a transfer node ("Capture: <node>") copies the last version of each texture the
// node wrote (single-sample, one mip level, a format the host can decode) and of the opaque-depth
// and visibility buffers (the visibility-buffer path's images that live in buffers) into a readback
// buffer of its own. Being an old-version read, the graph orders each copy right after its node and
// before the next writer, and nothing the frame computes changes (the copies only read).
// Nodes that write only other buffers (culling, light lists) have no images: their counts come from
// the workload's stats. Without --capture this feature declares nothing.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "../context/render_feature.hpp"

namespace fgb::features {

// What a captured image holds, which decides how the host decodes and stores it.
enum class CapturedContent : uint8_t {
  Color,       // a float or 8-bit colour texture
  Depth,       // a depth texture or the opaque-depth buffer: one float per pixel
  Visibility,  // the visibility words: uint64 per pixel, depth key << 32 | draw << 7 | triangle
};

struct CapturedBytes {
  std::string pass;
  std::string resource;
  CapturedContent content = CapturedContent::Color;
  graph::Format format = graph::Format::Undefined;  // textures; Undefined for buffers
  graph::Extent extent;
  std::vector<std::byte> bytes;  // tightly packed rows, top row first
};

class PassCaptureFeature final : public IRenderFeature {
 public:
  // `nodes`: the node names to capture; empty = every node with an image output.
  explicit PassCaptureFeature(std::vector<std::string> nodes) : wanted_(std::move(nodes)) {}
  [[nodiscard]] std::string_view name() const override { return "pass capture"; }
  [[nodiscard]] bool enabled() const override { return enabled_; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

  // The last rendered frame's captures, in declaration order of their nodes (call after the GPU
  // finished it).
  [[nodiscard]] std::vector<CapturedBytes> read() const;

 private:
  struct Target {
    std::string resource;
    CapturedContent content = CapturedContent::Color;
    graph::Format format = graph::Format::Undefined;
    graph::Extent extent;
    graph::TextureHandle texture;  // one of the two is valid
    graph::BufferHandle buffer;
    uint64_t offset = 0;
    uint64_t bytes = 0;
  };
  struct Captured {
    std::string pass;
    std::vector<Target> targets;
    rhi::BufferId readback;
  };

  [[nodiscard]] std::vector<Target> targetsOf(const graph::FrameGraph& graph, uint32_t node,
                                              const Blackboard& board) const;
  void declareCopy(graph::FrameGraph& graph, Captured& captured);

  std::vector<std::string> wanted_;
  rhi::Device* device_ = nullptr;
  bool enabled_ = false;
  graph::Extent sceneExtent_;  // the scene passes' size: the visibility buffers' rows
  std::vector<Captured> captured_;
};

// True where the host can decode this texture format into RGBA floats (capture and readback).
bool capturableFormat(graph::Format format);

}  // namespace fgb::features
