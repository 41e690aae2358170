// IRenderFeature: one renderer feature (meshes, lights, particles, bloom, ...). A feature creates
// its pipelines and persistent resources once, then declares its frame-graph nodes, reading and
// publishing graph handles through the blackboard. Node names match the thesis' table.
#pragma once

#include "blackboard.hpp"
#include "gpu_scene.hpp"
#include "handles.hpp"
#include "render_path.hpp"
#include "render_settings.hpp"
#include "renderer/shared/opaque_depth.h"

#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/command_buffer.hpp>
#include <fgb/rhi/device.hpp>
#include <fgb/rhi/job_context.hpp>

#include <map>
#include <string>
#include <string_view>

namespace fgb::features {

struct FeatureInit {
  rhi::Device& device;
  const GpuScene& scene;
  const RenderSettings& settings;
  // The path's decisions (post-pass form, depth test, ...); the feature's own options come through
  // its registry entry's factory.
  const RenderPath& path;
};

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

// The execution's copies of the per-frame buffers (FrameBuffers) into a push block: the camera,
// frustum planes and HiZ flag (frame), render-space instances, and the lights where the block has them.
template <class Push>
void useFrame(Push& push, const GpuScene& scene, uint64_t execution) {
  const FrameBuffers& frame = scene.frame(execution);
  push.frame = frame.constantsIndex;
  push.instances = frame.instancesIndex;
  if constexpr (requires { push.lights; }) push.lights = frame.lightsIndex;
}

// The light lists of clustered lighting, where the path has them ("Clustered Light Cull"
// published them): declares the node's reads of them in `stages`. Invalid handles where it has none.
ClusteredLights readLightLists(graph::NodeBuilder& node, const Blackboard& board,
                               graph::StageMask stages = graph::kStageNone);
// Their storage-buffer indices into a shading push block; left as they are where there are none
// (the shaders then read every light).
template <class Push>
void useLightLists(Push& push, rhi::JobContext& ctx, const ClusteredLights& lists) {
  if (!lists.counts.valid()) return;
  push.clusterCounts = ctx.storageBufferIndex(lists.counts);
  push.clusterIndices = ctx.storageBufferIndex(lists.indices);
}

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

// The pipeline's depth state for `form`: the depth format and kDepthCompare, writing when asked;
// none for OpaqueDepthBuffer (which cannot write depth: std::logic_error).
void setDepthState(rhi::GraphicsPipelineDesc& desc, DepthTest form, bool writesDepth);

// What a colour pass's job needs to fill gpu::OpaqueDepthTest (a push-constant member): the opaque depth buffer of the
// visibility-buffer path (invalid with the Attachment form, or when nothing opaque was drawn: every
// fragment then passes, as against a cleared attachment) and its row stride.
struct OpaqueDepthSource {
  graph::BufferHandle buffer;
  uint32_t rowStride = 0;
  [[nodiscard]] gpu::OpaqueDepthTest push(rhi::JobContext& ctx) const;
};

// Convenience: one forward colour pass over FrameTargets::color (the first clears, later ones
// load); with MSAA nothing is resolved here: MsaaResolveFeature (features/ssaa) does that after the
// last colour pass, and a colour pass declared after it throws std::logic_error. With
// DepthTest::OpaqueDepthBuffer the pass has no depth attachment and declares a storage read of
// FrameTargets::opaqueDepth (if any) instead, for its fragment shader's test; it cannot write
// depth (std::logic_error). Returns the builder so the caller can add reads and the job.
graph::NodeBuilder addForwardPass(graph::FrameGraph& graph, FrameTargets& targets, std::string_view name,
                                  bool writesDepth, DepthTest depthTest = DepthTest::Attachment);
// The opaque depth a pass declared by addForwardPass with `depthTest` tests against.
[[nodiscard]] OpaqueDepthSource opaqueDepthSource(const FrameTargets& targets, DepthTest depthTest);

// How features read statistics back: a zero-filled host-readable buffer of `bytes` (created once),
// into which a side-effect transfer node `nodeName` copies `source` every frame. The graph imports
// the buffer under its own `name`; the host reads it through Device::mapped() after the frame.
rhi::BufferId createReadbackBuffer(rhi::Device& device, const std::string& name, uint64_t bytes);
void declareReadback(graph::FrameGraph& graph, std::string_view nodeName, graph::BufferHandle source,
                     rhi::BufferId readback, std::string_view name, uint64_t bytes);

}  // namespace fgb::features
