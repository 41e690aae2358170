#include "ssaa_resolve_feature.hpp"

#include <fgb/rhi/job_context.hpp>

namespace fgb::features {
namespace {

// Mirrors the push block of shaders/renderer/ssaa_resolve.frag.
struct ResolvePush {
  uint32_t source;
  uint32_t factor;
};

}  // namespace

void SsaaResolveFeature::initialize(FeatureInit& init) {
  factor_ = init.settings.ssaa;
  if (!enabled()) return;
  rhi::GraphicsPipelineDesc desc;
  desc.name = "ssaa resolve";
  desc.vertexShader = "common/fullscreen.vert";
  desc.fragmentShader = "renderer/ssaa_resolve.frag";
  desc.colorFormats = {kHdrFormat};
  pipeline_ = init.device.createGraphicsPipeline(desc);
}

void SsaaResolveFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  auto& targets = board.get<FrameTargets>();
  if (!targets.colorResolved) throw std::logic_error("SSAA Resolve declared before the MSAA resolve");
  auto node = graph.addNode("SSAA Resolve", graph::NodeType::Graphics);
  const graph::TextureHandle source = node.read(targets.hdr, graph::Access::Sampled, graph::kStageFragmentShader);
  // Every output pixel is written, so the previous contents are not loaded.
  targets.hdr = node.addColorTarget(targets.outputHdr, graph::LoadOp::DontCare);
  targets.outputHdr = {};
  targets.extent = targets.outputExtent;
  node.setJob([pipeline = pipeline_, source, factor = factor_](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    const ResolvePush push{ctx.sampledTextureIndex(source), factor};
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().draw(3);
  });
}

}  // namespace fgb::features
