#include "tonemap_feature.hpp"

#include <fgb/rhi/job_context.hpp>

#include "../context/handles.hpp"
#include "renderer/shared/post.h"

namespace fgb::features {

graph::Format TonemapFeature::displayFormat(PostPassForm form) {
  return form == PostPassForm::Compute ? graph::Format::R8G8B8A8Unorm : kDisplayFormat;
}

void TonemapFeature::initialize(FeatureInit& init) {
  form_ = init.path.post;
  pipeline_ = createPostPassPipeline(init.device, form_, "tone mapping", "tonemap", kDisplayFormat);
  samplerIndex_ = init.device.samplerIndex(init.scene.linearClampSampler);
  exposureBuffer_ = init.device.storageBufferIndex(init.scene.exposure);
  bloomIntensity_ = init.scene.scene->post.bloom.intensity;
  injectBias_ = init.settings.injectBiasPass == "Tone mapping";
}

void TonemapFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  auto& targets = board.get<FrameTargets>();
  const bool compute = form_ == PostPassForm::Compute;
  const graph::StageMask stage = postPassStage(form_);
  auto node = addPostPassNode(graph, form_, "Tone mapping");
  const graph::TextureHandle hdr = node.read(targets.hdr, graph::Access::Sampled, stage);
  graph::TextureHandle bloom;
  if (const auto* published = board.find<BloomOutput>()) {
    bloom = published->texture;
    node.read(bloom, graph::Access::Sampled, stage);
  }
  if (targets.exposure.valid()) node.read(targets.exposure, graph::Access::StorageRead, stage);
  targets.display = writePostPassOutput(node, form_, targets.display);
  gpu::TonemapPush push{0,
                        rhi::kInvalidId,
                        samplerIndex_,
                        exposureBuffer_,
                        bloomIntensity_,
                        rhi::kInvalidId,
                        injectBias_ ? gpu::kInjectedBias : 0.0f};
  const graph::Extent extent = targets.outputExtent;
  node.setJob([push, pipeline = pipeline_, hdr, bloom, display = targets.display, form = form_, compute,
               extent](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.hdrTexture = ctx.sampledTextureIndex(hdr);
    if (bloom.valid()) push.bloomTexture = ctx.sampledTextureIndex(bloom);
    if (compute) push.display = ctx.storageTextureIndex(display);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    recordPostPass(ctx.cmd(), form, extent);
  });
  node.recordingFixed();
}

}  // namespace fgb::features
