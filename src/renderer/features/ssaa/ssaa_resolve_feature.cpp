#include "ssaa_resolve_feature.hpp"

#include <fgb/rhi/job_context.hpp>

#include "renderer/shared/post.h"

namespace fgb::features {

void SsaaResolveFeature::initialize(FeatureInit& init) {
  factor_ = init.settings.ssaa;
  form_ = init.path.post;
  if (!enabled()) return;
  pipeline_ = createPostPassPipeline(init.device, form_, "ssaa resolve", "ssaa_resolve", kHdrFormat);
}

void SsaaResolveFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  auto& targets = board.get<FrameTargets>();
  if (!targets.colorResolved) throw std::logic_error("SSAA Resolve declared before the MSAA resolve");
  const bool compute = form_ == PostPassForm::Compute;
  auto node = addPostPassNode(graph, form_, "SSAA Resolve");
  const graph::TextureHandle source = node.read(targets.hdr, graph::Access::Sampled, postPassStage(form_));
  targets.hdr = writePostPassOutput(node, form_, targets.outputHdr);
  targets.outputHdr = {};
  targets.extent = targets.outputExtent;
  node.setJob([pipeline = pipeline_, source, target = targets.hdr, factor = factor_, form = form_, compute,
               extent = targets.extent](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    const gpu::SsaaResolvePush push{ctx.sampledTextureIndex(source), factor,
                                    compute ? ctx.storageTextureIndex(target) : rhi::kInvalidId};
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    recordPostPass(ctx.cmd(), form, extent);
  });
  node.recordingFixed();
}

}  // namespace fgb::features
