#include "ssaa_resolve_feature.hpp"

#include <fgb/rhi/job_context.hpp>

namespace fgb::features {
namespace {

// Mirrors the push block of shaders/renderer/include/ssaa.glsl.
struct ResolvePush {
  uint32_t source;
  uint32_t factor;
  uint32_t target;  // compute form only
};

constexpr uint32_t kGroupSize = 8;  // ssaa_resolve.comp's local size (8 x 8)

}  // namespace

void SsaaResolveFeature::initialize(FeatureInit& init) {
  factor_ = init.settings.ssaa;
  if (!enabled()) return;
  if (form_ == PostPassForm::Compute) {
    pipeline_ = init.device.createComputePipeline({"ssaa resolve", "renderer/ssaa_resolve.comp"});
    return;
  }
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
  const bool compute = form_ == PostPassForm::Compute;
  auto node = compute ? graph.addNode("SSAA Resolve", graph::NodeType::Compute, graph::QueueClass::Graphics)
                      : graph.addNode("SSAA Resolve", graph::NodeType::Graphics);
  const graph::TextureHandle source = node.read(targets.hdr, graph::Access::Sampled,
                                                compute ? graph::kStageComputeShader : graph::kStageFragmentShader);
  // Every output pixel is written, so the previous contents are not loaded.
  targets.hdr = compute ? node.write(targets.outputHdr, graph::Access::StorageWrite)
                        : node.addColorTarget(targets.outputHdr, graph::LoadOp::DontCare);
  targets.outputHdr = {};
  targets.extent = targets.outputExtent;
  node.setJob([pipeline = pipeline_, source, target = targets.hdr, factor = factor_, compute,
               extent = targets.extent](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    const ResolvePush push{ctx.sampledTextureIndex(source), factor,
                           compute ? ctx.storageTextureIndex(target) : rhi::kInvalidId};
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    if (compute) {
      ctx.cmd().dispatch((extent.width + kGroupSize - 1) / kGroupSize, (extent.height + kGroupSize - 1) / kGroupSize);
    } else {
      ctx.cmd().draw(3);
    }
  });
}

}  // namespace fgb::features
