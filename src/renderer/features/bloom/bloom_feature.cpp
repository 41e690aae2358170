#include "bloom_feature.hpp"

#include "../context/handles.hpp"
#include "renderer/shared/post.h"

#include <fgb/rhi/job_context.hpp>

#include <algorithm>
#include <array>
#include <vector>
#include <string>

namespace fgb::features {
namespace {

// Size of level `level` of the chain (level 0 = the HDR image), as the graph resolves it.
graph::Extent levelExtent(const graph::Extent& full, uint32_t level) {
  return {std::max(1u, full.width >> level), std::max(1u, full.height >> level), 1};
}

void dispatchOver(rhi::CommandBuffer& cmd, const graph::Extent& size) {
  cmd.dispatch((size.width + FGB_BLOOM_GROUP_SIZE - 1) / FGB_BLOOM_GROUP_SIZE,
               (size.height + FGB_BLOOM_GROUP_SIZE - 1) / FGB_BLOOM_GROUP_SIZE);
}

}  // namespace

void BloomFeature::initialize(FeatureInit& init) {
  bloom_ = init.scene.scene->post.bloom;
  injectNan_ = init.settings.injectNanPass == "Bloom";
  injectBias_ = init.settings.injectBiasPass == "Bloom";
  // Nothing drawn (no instances, no particles): the cleared background has nothing to bloom.
  const bool drawsSomething = !init.scene.scene->instances.empty() || !init.scene.scene->emitters.empty();
  enabled_ = bloom_.enabled && bloom_.intensity > 0.0f && drawsSomething;
  if (!enabled_) return;
  // Stop before a level would be smaller than 2x2.
  const uint32_t smallest = std::min(init.settings.width, init.settings.height);
  mips_ = 0;
  while (mips_ < init.settings.bloomMips && (smallest >> (mips_ + 1)) >= 2) ++mips_;
  enabled_ = mips_ > 0;
  downPipeline_ = init.device.createComputePipeline({"bloom downsample", "renderer/bloom_down.comp"});
  upPipeline_ = init.device.createComputePipeline({"bloom upsample", "renderer/bloom_up.comp"});
  samplerIndex_ = init.device.samplerIndex(init.scene.linearClampSampler);
  exposureIndex_ = init.device.storageBufferIndex(init.scene.exposure);
}

void BloomFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled_) return;
  const auto& targets = board.get<FrameTargets>();
  auto node = graph.addNode("Bloom", graph::NodeType::Compute, graph::QueueClass::Graphics);
  const auto hdr = node.read(targets.hdr, graph::Access::Sampled);
  if (targets.exposure.valid()) node.read(targets.exposure, graph::Access::StorageRead);
  std::vector<graph::TextureHandle> levels(size_t{mips_} + 1);  // [0] unused: the HDR image
  for (uint32_t level = 1; level <= mips_; ++level) {
    const auto texture = graph.createTexture("bloom " + std::to_string(level), {kHdrFormat, {}, 1, 1, 1, targets.hdr, level});
    // Written first (the downsample), then sampled and added to inside the node (barriers in the
    // job); sampled in GENERAL, so the texture unit filters the taps.
    levels[level] = node.write(texture, graph::Access::StorageSampledWrite);
  }
  std::vector<graph::Extent> sizes(size_t{mips_} + 1);
  for (uint32_t level = 0; level <= mips_; ++level) sizes[level] = levelExtent(targets.extent, level);

  node.setJob([down = downPipeline_, up = upPipeline_, sampler = samplerIndex_, bloom = bloom_, mips = mips_, hdr,
               levels, sizes, exposure = exposureIndex_, injectNan = injectNan_,
               injectBias = injectBias_](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    const auto xy = [](const graph::Extent& e) { return glm::ivec2(int32_t(e.width), int32_t(e.height)); };
    cmd.bindPipeline(down);
    for (uint32_t level = 1; level <= mips; ++level) {
      if (level > 1) cmd.computeBarrier();  // reads the level the previous dispatch wrote
      const bool first = level == 1;
      const gpu::BloomDownPush push{
          first ? ctx.sampledTextureIndex(hdr) : ctx.sampledGeneralTextureIndex(levels[level - 1]),
          sampler,
          ctx.storageTextureIndex(levels[level]),
          first ? 1u : 0u,
          xy(sizes[level - 1]),
          xy(sizes[level]),
          bloom.threshold,
          bloom.knee,
          exposure,
          first && injectNan ? gpu::kInjectNan : 0u};
      cmd.push(push);
      dispatchOver(cmd, sizes[level]);
    }
    cmd.bindPipeline(up);
    for (uint32_t level = mips; level >= 2; --level) {
      cmd.computeBarrier();
      // debug.inject_nan / inject_bias=Bloom: the last write of level 1 (the level tone mapping reads)
      // holds the NaN or the bias.
      const gpu::BloomUpPush push{ctx.sampledGeneralTextureIndex(levels[level]),
                                  ctx.storageTextureIndex(levels[level - 1]),
                                  xy(sizes[level]),
                                  xy(sizes[level - 1]),
                                  bloom.radius,
                                  level != 2   ? 0u
                                  : injectNan  ? gpu::kInjectNan
                                  : injectBias ? gpu::kInjectBias
                                               : 0u,
                                  sampler};
      cmd.push(push);
      dispatchOver(cmd, sizes[level - 1]);
    }
  });
  node.recordingFixed();
  board.set(BloomOutput{levels[1]});
}

}  // namespace fgb::features
