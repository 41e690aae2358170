#include "exposure_feature.hpp"

#include <fgb/rhi/job_context.hpp>

#include "renderer/shared/post.h"

namespace fgb::features {
namespace {

constexpr uint32_t kBlock = 2 * FGB_LUMINANCE_GROUP_SIZE;  // pixels per reduce workgroup side (2x2 per invocation)

}  // namespace

void ExposureFeature::initialize(FeatureInit& init) {
  enabled_ = init.scene.scene->post.autoExposure;
  if (!enabled_) return;
  reducePipeline_ = init.device.createComputePipeline({"luminance reduce", "renderer/luminance_reduce.comp"});
  updatePipeline_ = init.device.createComputePipeline({"exposure update", "renderer/exposure_update.comp"});
  stateIndex_ = init.device.storageBufferIndex(init.scene.exposure);
}

void ExposureFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled_) return;
  auto& targets = board.get<FrameTargets>();
  const uint32_t groupsX = (targets.extent.width + kBlock - 1) / kBlock;
  const uint32_t groupsY = (targets.extent.height + kBlock - 1) / kBlock;
  // On the graphics queue, like every other user of the exposure state: no ownership transfers.
  auto node = graph.addNode("Exposure", graph::NodeType::Compute, graph::QueueClass::Graphics);
  const auto hdr = node.read(targets.hdr, graph::Access::Sampled);
  auto partials = graph.createBuffer("luminance partials", {uint64_t{16} * groupsX * groupsY, {}});
  partials = node.write(partials, graph::Access::StorageWrite);  // then read back in the job, after a barrier
  targets.exposure = node.write(targets.exposure, graph::Access::StorageReadWrite);
  gpu::LuminanceReducePush reduce{0, 0, {int32_t(targets.extent.width), int32_t(targets.extent.height)}};
  gpu::ExposureUpdatePush update{0, groupsX * groupsY, stateIndex_, kKey};
  node.setJob([reduce, update, groupsX, groupsY, hdr, partials, reducePipeline = reducePipeline_,
               updatePipeline = updatePipeline_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    auto& cmd = ctx.cmd();
    reduce.hdr = ctx.sampledTextureIndex(hdr);
    reduce.partials = update.partials = ctx.storageBufferIndex(partials);
    cmd.bindPipeline(reducePipeline);
    cmd.push(reduce);
    cmd.dispatch(groupsX, groupsY);
    cmd.computeBarrier();  // the update reads every workgroup's partial sum
    cmd.bindPipeline(updatePipeline);
    cmd.push(update);
    cmd.dispatch(1);
  });
  node.recordingFixed();
}

}  // namespace fgb::features
