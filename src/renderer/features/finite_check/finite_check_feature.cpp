#include "finite_check_feature.hpp"

#include <algorithm>
#include <cstring>
#include <fgb/rhi/job_context.hpp>

#include "renderer/shared/post.h"

namespace fgb::features {
namespace {

using graph::Access;

bool isFloatColor(graph::Format format) {
  switch (format) {
    case graph::Format::R16G16B16A16Sfloat:
    case graph::Format::R32G32B32A32Sfloat:
    case graph::Format::R16G16Sfloat:
    case graph::Format::R32Sfloat:
      return true;
    default:
      return false;
  }
}

// A texture's size as the compiler will resolve it (dependent extents follow extentFrom).
graph::Extent extentOf(const graph::FrameGraph& graph, uint32_t resource) {
  const graph::TextureDesc& desc = graph.resources()[resource].texture;
  if (!desc.extentFrom.valid()) return desc.extent;
  const graph::Extent base = extentOf(graph, graph.resourceOf(desc.extentFrom));
  return {std::max(1u, base.width >> desc.extentShift), std::max(1u, base.height >> desc.extentShift), 1};
}

}  // namespace

void FiniteCheckFeature::initialize(FeatureInit& init) {
  enabled_ = init.settings.checkFinite;
  device_ = &init.device;
  if (!enabled_) return;
  singleSample_ = init.device.createComputePipeline({"finite check", "renderer/finite_check.comp"});
  multiSample_ = init.device.createComputePipeline({"finite check (msaa)", "renderer/finite_check_ms.comp"});
}

std::vector<FiniteCheckFeature::Checked> FiniteCheckFeature::findCheckedPasses(const graph::FrameGraph& graph) const {
  std::vector<Checked> passes;
  for (uint32_t node = 0; node < graph.nodes().size(); ++node) {
    Checked checked{node, std::string(graph.nodes()[node].name), {}};
    for (const graph::ResourceAccess& use : graph.accesses(node)) {
      const graph::ResourceDecl& resource = graph.resources()[use.resource];
      if (use.writeVersion == graph::kInvalidIndex || resource.kind != graph::ResourceKind::Texture) continue;
      if (!isFloatColor(resource.texture.format)) continue;
      checked.textures.push_back({{use.writeVersion}, extentOf(graph, use.resource), resource.texture.samples});
    }
    if (!checked.textures.empty()) passes.push_back(std::move(checked));
  }
  return passes;
}

void FiniteCheckFeature::declareCheck(graph::FrameGraph& graph, const Checked& checked, uint32_t slot,
                                      graph::BufferHandle& counters) {
  // On the graphics queue, like the passes it checks: no ownership transfers for their textures.
  auto node = graph.addNode("Finite Check: " + checked.pass, graph::NodeType::Compute, graph::QueueClass::Graphics);
  for (const Written& written : checked.textures) node.read(written.texture, Access::Sampled);
  counters = node.write(counters, Access::StorageReadWrite);
  node.setJob([textures = checked.textures, slot, counters, single = singleSample_,
               multi = multiSample_](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    for (const Written& written : textures) {
      const gpu::FiniteCheckPush push{ctx.sampledTextureIndex(written.texture),
                                      ctx.storageBufferIndex(counters),
                                      slot,
                                      written.samples,
                                      {int32_t(written.extent.width), int32_t(written.extent.height)}};
      ctx.cmd().bindPipeline(written.samples > 1 ? multi : single);
      ctx.cmd().push(push);
      ctx.cmd().dispatch((written.extent.width + FGB_FINITE_CHECK_GROUP_SIZE - 1) / FGB_FINITE_CHECK_GROUP_SIZE,
                         (written.extent.height + FGB_FINITE_CHECK_GROUP_SIZE - 1) / FGB_FINITE_CHECK_GROUP_SIZE);
    }
  });
  node.recordingFixed();
}

void FiniteCheckFeature::declare(graph::FrameGraph& graph, Blackboard& /*board*/) {
  if (!enabled_) return;
  checked_ = findCheckedPasses(graph);
  if (checked_.empty()) return;
  const uint64_t bytes = uint64_t{gpu::kFiniteCheckSlotBytes} * checked_.size();
  graph::BufferHandle counters = graph.createBuffer("finite check counters", {bytes, {}});
  auto reset = graph.addNode("Finite Check Reset", graph::NodeType::Transfer, graph::QueueClass::Graphics);
  counters = reset.write(counters, Access::TransferDst);
  reset.setJob([counters, bytes](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().fillBuffer(ctx.buffer(counters), 0, bytes, 0);
  });
  reset.recordingFixed();
  for (uint32_t slot = 0; slot < checked_.size(); ++slot) declareCheck(graph, checked_[slot], slot, counters);

  readback_ =
      device_->createBuffer({"finite check readback", bytes, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  std::memset(device_->mapped(readback_).data(), 0, bytes);
  const graph::ImportState hostState{graph::kStageHost | graph::kStageTransfer,
                                     graph::kAccessHostRead | graph::kAccessTransferWrite, graph::Layout::Undefined,
                                     graph::QueueClass::Graphics};
  auto target =
      graph.importBuffer("finite check readback", {bytes, {}}, rhi::external(readback_), hostState, hostState);
  auto copy = graph.addNode("Finite Check Readback", graph::NodeType::Transfer, graph::QueueClass::Graphics);
  copy.read(counters, Access::TransferSrc);
  target = copy.write(target, Access::TransferDst);
  copy.sideEffect();
  copy.setJob([counters, target, bytes](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().copyBuffer(ctx.buffer(counters), ctx.buffer(target), bytes);
  });
  copy.recordingFixed();
}

std::vector<PassFiniteCounts> FiniteCheckFeature::counts() const {
  std::vector<PassFiniteCounts> result;
  if (checked_.empty()) return result;
  std::vector<uint32_t> values(checked_.size() * 4);
  std::memcpy(values.data(), device_->mapped(readback_).data(), values.size() * sizeof(uint32_t));
  for (size_t slot = 0; slot < checked_.size(); ++slot) {
    result.push_back(
        {checked_[slot].pass, checked_[slot].node, values[slot * 4], values[slot * 4 + 1], values[slot * 4 + 2]});
  }
  return result;
}

}  // namespace fgb::features
