#include "tonemap_feature.hpp"

#include "../context/handles.hpp"

#include <fgb/rhi/job_context.hpp>

namespace fgb::features {
namespace {

// Mirrors the push block of shaders/renderer/include/tonemap.glsl.
struct TonemapPush {
  uint32_t hdrTexture;
  uint32_t bloomTexture;
  uint32_t linearSampler;
  uint32_t exposure;
  float bloomIntensity;
  uint32_t display;  // compute form only
};

constexpr uint32_t kGroupSize = 8;  // tonemap.comp's local size (8 x 8)

}  // namespace

graph::Format TonemapFeature::displayFormat(PostPassForm form) {
  return form == PostPassForm::Compute ? graph::Format::R8G8B8A8Unorm : kDisplayFormat;
}

void TonemapFeature::initialize(FeatureInit& init) {
  if (form_ == PostPassForm::Compute) {
    pipeline_ = init.device.createComputePipeline({"tone mapping", "renderer/tonemap.comp"});
  } else {
    rhi::GraphicsPipelineDesc desc;
    desc.name = "tone mapping";
    desc.vertexShader = "common/fullscreen.vert";
    desc.fragmentShader = "renderer/tonemap.frag";
    desc.colorFormats = {kDisplayFormat};
    pipeline_ = init.device.createGraphicsPipeline(desc);
  }
  samplerIndex_ = init.device.samplerIndex(init.scene.linearClampSampler);
  exposureBuffer_ = init.device.storageBufferIndex(init.scene.exposure);
  bloomIntensity_ = init.scene.scene->post.bloom.intensity;
}

void TonemapFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  auto& targets = board.get<FrameTargets>();
  const bool compute = form_ == PostPassForm::Compute;
  const graph::StageMask stage = compute ? graph::kStageComputeShader : graph::kStageFragmentShader;
  auto node = compute ? graph.addNode("Tone mapping", graph::NodeType::Compute, graph::QueueClass::Graphics)
                      : graph.addNode("Tone mapping", graph::NodeType::Graphics);
  const graph::TextureHandle hdr = node.read(targets.hdr, graph::Access::Sampled, stage);
  graph::TextureHandle bloom;
  if (const auto* published = board.find<BloomOutput>()) {
    bloom = published->texture;
    node.read(bloom, graph::Access::Sampled, stage);
  }
  if (targets.exposure.valid()) node.read(targets.exposure, graph::Access::StorageRead, stage);
  // Every display pixel is written, so the previous contents are not loaded.
  targets.display = compute ? node.write(targets.display, graph::Access::StorageWrite)
                            : node.addColorTarget(targets.display, graph::LoadOp::DontCare);
  TonemapPush push{0, rhi::kInvalidId, samplerIndex_, exposureBuffer_, bloomIntensity_, rhi::kInvalidId};
  const graph::Extent extent = targets.outputExtent;
  node.setJob([push, pipeline = pipeline_, hdr, bloom, display = targets.display, compute,
               extent](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.hdrTexture = ctx.sampledTextureIndex(hdr);
    if (bloom.valid()) push.bloomTexture = ctx.sampledTextureIndex(bloom);
    if (compute) push.display = ctx.storageTextureIndex(display);
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
