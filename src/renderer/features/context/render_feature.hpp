// IRenderFeature: one renderer feature (meshes, lights, particles, bloom, ...). A feature creates
// its pipelines and persistent resources once, then declares its frame-graph nodes, reading and
// publishing graph handles through the blackboard. Node names match the thesis' table.
#pragma once

#include "blackboard.hpp"
#include "gpu_scene.hpp"
#include "render_settings.hpp"

#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/command_buffer.hpp>
#include <fgb/rhi/device.hpp>

#include <map>
#include <string>
#include <string_view>

namespace fgb::features {

struct FeatureInit {
  rhi::Device& device;
  const GpuScene& scene;
  const RenderSettings& settings;
};

// How a full-screen post pass runs: as a fragment pass (the thesis' forward renderer) or as a
// compute dispatch on the graphics queue (the visibility-buffer path: on GPUs that run graphics on
// a few SMs only, compute reaches all of them). Both forms share their GLSL maths.
enum class PostPassForm : uint8_t { Fragment, Compute };

// The pipeline of a full-screen post pass in the given form: "renderer/<shader>.comp", or the
// full-screen triangle with "renderer/<shader>.frag" drawing into one `colorFormat` target.
rhi::PipelineId createPostPassPipeline(rhi::Device& device, PostPassForm form, const std::string& name,
                                       const std::string& shader, graph::Format colorFormat);
// The node of a post pass in the given form: compute nodes run on the graphics queue.
graph::NodeBuilder addPostPassNode(graph::FrameGraph& graph, PostPassForm form, std::string_view name);
// The shader stage a post pass reads its inputs in.
graph::StageMask postPassStage(PostPassForm form);
// Declares the pass's one output; every pixel is written, so the previous contents are not loaded.
graph::TextureHandle writePostPassOutput(graph::NodeBuilder& node, PostPassForm form, graph::TextureHandle target);
// Records the pass's work after its pipeline and push constants: one invocation per pixel of
// `extent` (the .comp shaders' 8 x 8 local size) or the full-screen triangle.
void recordPostPass(rhi::CommandBuffer& cmd, PostPassForm form, const graph::Extent& extent);

class IRenderFeature {
 public:
  virtual ~IRenderFeature() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  // False when the scene needs none of this feature's work: it then declares nothing.
  [[nodiscard]] virtual bool enabled() const { return true; }
  // Once per run, after the scene upload: pipelines and persistent GPU resources.
  virtual void initialize(FeatureInit& init) = 0;
  // Declares this frame's nodes. Called once; the compiled graph is executed every frame.
  virtual void declare(graph::FrameGraph& graph, Blackboard& board) = 0;
  // Adds run statistics (read back from the GPU where needed) after frames were rendered.
  virtual void addStats(std::map<std::string, double>& /*stats*/) const {}
};

// Convenience: one forward colour pass over FrameTargets::color (the first clears, later ones
// load); with MSAA nothing is resolved here: MsaaResolveFeature (features/ssaa) does that after the
// last colour pass, and a colour pass declared after it throws std::logic_error. Returns the builder
// so the caller can add reads and the job.
graph::NodeBuilder addForwardPass(graph::FrameGraph& graph, FrameTargets& targets, std::string_view name,
                                  bool writesDepth);

// How features read statistics back: a zero-filled host-readable buffer of `bytes` (created once),
// into which a side-effect transfer node `nodeName` copies `source` every frame. The graph imports
// the buffer under its own `name`; the host reads it through Device::mapped() after the frame.
rhi::BufferId createReadbackBuffer(rhi::Device& device, const std::string& name, uint64_t bytes);
void declareReadback(graph::FrameGraph& graph, std::string_view nodeName, graph::BufferHandle source,
                     rhi::BufferId readback, std::string_view name, uint64_t bytes);

}  // namespace fgb::features
