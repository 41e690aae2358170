// The built-in proof scene "builtin:proof" (issue 2): a small graph exercising every node type —
//   Pattern (compute)        writes the vertices of a fan of HDR-coloured triangles;
//   Draw pattern (graphics)  draws them into an RGBA16F target (MSAA + resolve when msaa > 1);
//   Tone map (graphics)      1 - exp(-hdr * exposure) into an sRGB display target;
//   Readback (transfer)      copies HDR and display images into host-visible buffers (side effect);
//   Debug luminance (compute) writes a buffer nobody reads: the compiler culls it.
// Knobs (--set): exposure (0.6), triangles (12), speed (0: static; radians/4 per frame), queues (0),
// separate-queues (0; 1 keeps logical queues apart on a one-queue device, see rhi::GraphOptions).
#pragma once

#include <fgb/graph/frame_graph.hpp>
#include <fgb/renderer/workload.hpp>
#include <fgb/rhi/device.hpp>

#include <memory>

namespace fgb::render {

struct ProofSettings {
  uint32_t width = 320;
  uint32_t height = 180;
  uint32_t msaa = 4;
  float exposure = 0.6f;
  uint32_t triangles = 12;
  float speed = 0.0f;
  uint32_t queues = 0;  // logical queues (0: one per distinct device queue family)
  bool separateQueues = false;
};

// Device objects the proof graph uses (created once).
struct ProofResources {
  rhi::PipelineId pattern, draw, tonemap, luminance;
  rhi::SamplerId pointSampler;
  uint32_t pointSamplerIndex = rhi::kInvalidId;
  rhi::BufferId hdrReadback, displayReadback;
};

ProofSettings proofSettings(const WorkloadConfig& config, uint32_t deviceSampleCounts);  // rhi::Device::sampleCounts()
ProofResources createProofResources(rhi::Device& device, const ProofSettings& settings);
graph::FrameGraph buildProofGraph(const ProofSettings& settings, const ProofResources& resources);

std::unique_ptr<Workload> openProofWorkload(const WorkloadConfig& config);

}  // namespace fgb::render
