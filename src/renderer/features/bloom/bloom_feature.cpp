#include "bloom_feature.hpp"

#include "../context/handles.hpp"

#include <fgb/rhi/job_context.hpp>

#include <algorithm>
#include <string>

namespace fgb::features {
namespace {

// Mirror the push blocks of shaders/renderer/bloom_down.frag and bloom_up.frag.
struct DownPush {
  uint32_t source;
  uint32_t linearSampler;
  float sourceTexel[2];
  uint32_t firstMip;
  float threshold;
  float knee;
};
struct UpPush {
  uint32_t source;
  uint32_t linearSampler;
  float sourceTexel[2];
  float radius;
};

// Size of level `level` of the chain (level 0 = the HDR image), as the graph resolves it.
graph::Extent levelExtent(const graph::Extent& full, uint32_t level) {
  return {std::max(1u, full.width >> level), std::max(1u, full.height >> level), 1};
}

rhi::GraphicsPipelineDesc pipelineDesc(const char* name, const char* shader, rhi::BlendMode blend) {
  rhi::GraphicsPipelineDesc desc;
  desc.name = name;
  desc.vertexShader = "common/fullscreen.vert";
  desc.fragmentShader = shader;
  desc.colorFormats = {kHdrFormat};
  desc.blend = {blend};
  return desc;
}

}  // namespace

void BloomFeature::initialize(FeatureInit& init) {
  bloom_ = init.scene.scene->post.bloom;
  // Nothing drawn (no instances, no particles): the cleared background has nothing to bloom.
  const bool drawsSomething = !init.scene.scene->instances.empty() || !init.scene.scene->emitters.empty();
  enabled_ = bloom_.enabled && bloom_.intensity > 0.0f && drawsSomething;
  if (!enabled_) return;
  // Stop before a level would be smaller than 2x2.
  const uint32_t smallest = std::min(init.settings.width, init.settings.height);
  mips_ = 0;
  while (mips_ < init.settings.bloomMips && (smallest >> (mips_ + 1)) >= 2) ++mips_;
  enabled_ = mips_ > 0;
  downPipeline_ = init.device.createGraphicsPipeline(pipelineDesc("bloom downsample", "renderer/bloom_down.frag", rhi::BlendMode::Opaque));
  upPipeline_ = init.device.createGraphicsPipeline(pipelineDesc("bloom upsample", "renderer/bloom_up.frag", rhi::BlendMode::Additive));
  samplerIndex_ = init.device.samplerIndex(init.scene.linearClampSampler);
}

void BloomFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled_) return;
  const auto& targets = board.get<FrameTargets>();
  std::vector<graph::TextureHandle> levels{targets.hdr};  // level 0: the HDR image
  levels.resize(size_t{mips_} + 1);
  for (uint32_t level = 1; level <= mips_; ++level) {
    levels[level] = graph.createTexture("bloom " + std::to_string(level), {kHdrFormat, {}, 1, 1, 1, targets.hdr, level});
    auto node = graph.addNode("Bloom Downsample " + std::to_string(level), graph::NodeType::Graphics);
    const auto source = node.read(levels[level - 1], graph::Access::Sampled, graph::kStageFragmentShader);
    levels[level] = node.addColorTarget(levels[level], graph::LoadOp::DontCare);
    const auto size = levelExtent(targets.extent, level - 1);
    DownPush push{0, samplerIndex_, {1.0f / float(size.width), 1.0f / float(size.height)}, level == 1 ? 1u : 0u,
                  bloom_.threshold, bloom_.knee};
    node.setJob([push, pipeline = downPipeline_, source](graph::JobContext& context) mutable {
      auto& ctx = rhi::rhiContext(context);
      push.source = ctx.sampledTextureIndex(source);
      ctx.cmd().bindPipeline(pipeline);
      ctx.cmd().push(push);
      ctx.cmd().draw(3);
    });
  }
  for (uint32_t level = mips_; level >= 2; --level) {
    auto node = graph.addNode("Bloom Upsample " + std::to_string(level), graph::NodeType::Graphics);
    const auto source = node.read(levels[level], graph::Access::Sampled, graph::kStageFragmentShader);
    levels[level - 1] = node.addColorTarget(levels[level - 1], graph::LoadOp::Load);
    const auto size = levelExtent(targets.extent, level);
    UpPush push{0, samplerIndex_, {1.0f / float(size.width), 1.0f / float(size.height)}, bloom_.radius};
    node.setJob([push, pipeline = upPipeline_, source](graph::JobContext& context) mutable {
      auto& ctx = rhi::rhiContext(context);
      push.source = ctx.sampledTextureIndex(source);
      ctx.cmd().bindPipeline(pipeline);
      ctx.cmd().push(push);
      ctx.cmd().draw(3);
    });
  }
  board.set(BloomOutput{levels[1]});
}

}  // namespace fgb::features
