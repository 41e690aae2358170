#include "tonemap_feature.hpp"

#include "../context/handles.hpp"

#include <fgb/rhi/job_context.hpp>

namespace fgb::features {
namespace {

// Mirrors the push block of shaders/renderer/tonemap.frag.
struct TonemapPush {
  uint32_t hdrTexture;
  uint32_t bloomTexture;
  uint32_t linearSampler;
  uint32_t exposure;
  float bloomIntensity;
};

}  // namespace

void TonemapFeature::initialize(FeatureInit& init) {
  rhi::GraphicsPipelineDesc desc;
  desc.name = "tone mapping";
  desc.vertexShader = "common/fullscreen.vert";
  desc.fragmentShader = "renderer/tonemap.frag";
  desc.colorFormats = {kDisplayFormat};
  pipeline_ = init.device.createGraphicsPipeline(desc);
  samplerIndex_ = init.device.samplerIndex(init.scene.linearClampSampler);
  exposureBuffer_ = init.device.storageBufferIndex(init.scene.exposure);
  bloomIntensity_ = init.scene.scene->post.bloom.intensity;
}

void TonemapFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  auto& targets = board.get<FrameTargets>();
  auto node = graph.addNode("Tone mapping", graph::NodeType::Graphics);
  const graph::TextureHandle hdr = node.read(targets.hdr, graph::Access::Sampled, graph::kStageFragmentShader);
  graph::TextureHandle bloom;
  if (const auto* published = board.find<BloomOutput>()) {
    bloom = published->texture;
    node.read(bloom, graph::Access::Sampled, graph::kStageFragmentShader);
  }
  if (targets.exposure.valid()) node.read(targets.exposure, graph::Access::StorageRead, graph::kStageFragmentShader);
  targets.display = node.addColorTarget(targets.display, graph::LoadOp::DontCare);
  TonemapPush push{0, rhi::kInvalidId, samplerIndex_, exposureBuffer_, bloomIntensity_};
  node.setJob([push, pipeline = pipeline_, hdr, bloom](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.hdrTexture = ctx.sampledTextureIndex(hdr);
    if (bloom.valid()) push.bloomTexture = ctx.sampledTextureIndex(bloom);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().draw(3);
  });
}

}  // namespace fgb::features
