#include "bloom_feature.hpp"

#include "../context/handles.hpp"
#include "renderer/shared/post.h"

#include <fgb/rhi/job_context.hpp>

#include <algorithm>
#include <array>
#include <vector>
#include <stdexcept>
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

// The first level bloom_tail.comp takes on: from level 2 (level 1 is read from the HDR image), the
// first whose texels fit FGB_BLOOM_TAIL_MAX_TEXELS, if at least two levels from it on do (one level
// alone is cheaper as an ordinary dispatch); otherwise mips + 1, no tail.
uint32_t tailStart(const std::vector<graph::Extent>& sizes, uint32_t mips) {
  for (uint32_t level = 2; level < mips; ++level)
    if (uint64_t{sizes[level].width} * sizes[level].height <= FGB_BLOOM_TAIL_MAX_TEXELS) return level;
  return mips + 1;
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
  if (mips_ >= FGB_BLOOM_MAX_LEVELS) throw std::logic_error("bloom.mips above what BloomTailPush holds");
  downPipeline_ = init.device.createComputePipeline({"bloom downsample", "renderer/bloom_down.comp"});
  upPipeline_ = init.device.createComputePipeline({"bloom upsample", "renderer/bloom_up.comp"});
  tailPipeline_ = init.device.createComputePipeline({"bloom tail", "renderer/bloom_tail.comp"});
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
    // Written first (the downsample), then read and added to inside the node (barriers in the job).
    levels[level] = node.write(texture, graph::Access::StorageWrite);
  }
  std::vector<graph::Extent> sizes(size_t{mips_} + 1);
  for (uint32_t level = 0; level <= mips_; ++level) sizes[level] = levelExtent(targets.extent, level);
  const uint32_t tail = tailStart(sizes, mips_);

  node.setJob([down = downPipeline_, up = upPipeline_, tailPipeline = tailPipeline_, tail, sampler = samplerIndex_, bloom = bloom_, mips = mips_, hdr,
               levels, sizes, exposure = exposureIndex_, injectNan = injectNan_,
               injectBias = injectBias_](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    const auto xy = [](const graph::Extent& e) { return glm::ivec2(int32_t(e.width), int32_t(e.height)); };
    cmd.bindPipeline(down);
    for (uint32_t level = 1; level < tail; ++level) {
      if (level > 1) cmd.computeBarrier();  // reads the level the previous dispatch wrote
      const bool first = level == 1;
      const gpu::BloomDownPush push{first ? ctx.sampledTextureIndex(hdr) : ctx.storageTextureIndex(levels[level - 1]),
                                    first ? 0u : 1u,
                                    sampler,
                                    ctx.storageTextureIndex(levels[level]),
                                    xy(sizes[level - 1]),
                                    xy(sizes[level]),
                                    first ? 1u : 0u,
                                    bloom.threshold,
                                    bloom.knee,
                                    exposure,
                                    first && injectNan ? gpu::kInjectNan : 0u};
      cmd.push(push);
      dispatchOver(cmd, sizes[level]);
    }
    if (tail <= mips) {
      cmd.computeBarrier();
      cmd.bindPipeline(tailPipeline);
      gpu::BloomTailPush push{};
      for (uint32_t level = 0; level <= mips; ++level)
        push.images[level] = level > 0 ? ctx.storageTextureIndex(levels[level]) : 0u;
      push.fullSize = xy(sizes[0]);
      push.firstLevel = tail;
      push.lastLevel = mips;
      push.radius = bloom.radius;
      cmd.push(push);
      cmd.dispatch(1);
    }
    cmd.bindPipeline(up);
    for (uint32_t level = std::min(mips, tail); level >= 2; --level) {
      cmd.computeBarrier();
      // debug.inject_nan / inject_bias=Bloom: the last write of level 1 (the level tone mapping reads)
      // holds the NaN or the bias.
      const gpu::BloomUpPush push{ctx.storageTextureIndex(levels[level]),
                                  ctx.storageTextureIndex(levels[level - 1]),
                                  xy(sizes[level]),
                                  xy(sizes[level - 1]),
                                  bloom.radius,
                                  level != 2   ? 0u
                                  : injectNan  ? gpu::kInjectNan
                                  : injectBias ? gpu::kInjectBias
                                               : 0u};
      cmd.push(push);
      dispatchOver(cmd, sizes[level - 1]);
    }
  });
  node.recordingFixed();
  board.set(BloomOutput{levels[1]});
}

}  // namespace fgb::features
