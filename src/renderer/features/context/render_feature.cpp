#include "render_feature.hpp"

#include <cstring>
#include <fgb/rhi/job_context.hpp>
#include <fgb/shaders/registry.hpp>

#include "renderer/shared/post.h"

namespace fgb::features {

rhi::PipelineId createPostPassPipeline(rhi::Device& device, PostPassForm form, const std::string& name,
                                       const std::string& shader, graph::Format colorFormat) {
  if (form == PostPassForm::Compute) return device.createComputePipeline({name, "renderer/" + shader + ".comp"});
  rhi::GraphicsPipelineDesc desc;
  desc.name = name;
  desc.vertexShader = "common/fullscreen.vert";
  desc.fragmentShader = "renderer/" + shader + ".frag";
  desc.colorFormats = {colorFormat};
  return device.createGraphicsPipeline(desc);
}

graph::NodeBuilder addPostPassNode(graph::FrameGraph& graph, PostPassForm form, std::string_view name) {
  return form == PostPassForm::Compute ? graph.addNode(name, graph::NodeType::Compute, graph::QueueClass::Graphics)
                                       : graph.addNode(name, graph::NodeType::Graphics);
}

graph::StageMask postPassStage(PostPassForm form) {
  return form == PostPassForm::Compute ? graph::kStageComputeShader : graph::kStageFragmentShader;
}

graph::TextureHandle writePostPassOutput(graph::NodeBuilder& node, PostPassForm form, graph::TextureHandle target) {
  return form == PostPassForm::Compute ? node.write(target, graph::Access::StorageWrite)
                                       : node.addColorTarget(target, graph::LoadOp::DontCare);
}

ClusteredLights readLightLists(graph::NodeBuilder& node, const Blackboard& board, graph::StageMask stages) {
  ClusteredLights lists;
  if (const auto* published = board.find<ClusteredLights>()) {
    lists = *published;
    node.read(lists.counts, graph::Access::StorageRead, stages);
    node.read(lists.indices, graph::Access::StorageRead, stages);
  }
  return lists;
}

void recordPostPass(rhi::CommandBuffer& cmd, PostPassForm form, const graph::Extent& extent) {
  if (form == PostPassForm::Compute) {
    cmd.dispatch((extent.width + FGB_POST_GROUP_SIZE - 1) / FGB_POST_GROUP_SIZE,
                 (extent.height + FGB_POST_GROUP_SIZE - 1) / FGB_POST_GROUP_SIZE);
  } else {
    cmd.draw(3);
  }
}
std::pair<uint32_t, uint32_t> GpuScene::groupRange(DrawClass drawClass) const {
  uint32_t first = 0;
  while (first < groups.size() && groups[first].drawClass < drawClass) ++first;
  uint32_t last = first;
  while (last < groups.size() && groups[last].drawClass == drawClass) ++last;
  return {first, last - first};
}

void setDepthState(rhi::GraphicsPipelineDesc& desc, DepthTest form, bool writesDepth) {
  if (form == DepthTest::OpaqueDepthBuffer) {
    if (writesDepth) throw std::logic_error("pipeline '" + desc.name + "' writes depth: it needs a depth attachment");
    desc.depthFormat = graph::Format::Undefined;
    desc.depthTest = desc.depthWrite = false;
    // The fragment shader's variant that tests the opaque depth (shaders/CMakeLists.txt).
    desc.fragmentShader = shaders::variantPath(desc.fragmentShader, "opaque_depth");
    return;
  }
  desc.depthFormat = kDepthFormat;
  desc.depthTest = true;
  desc.depthWrite = writesDepth;
  desc.depthCompare = kDepthCompare;
}

gpu::OpaqueDepthTest OpaqueDepthSource::push(rhi::JobContext& ctx) const {
  gpu::OpaqueDepthTest test{FGB_NONE, 0, 0};  // nothing to test against: every fragment passes
  if (!buffer.valid()) return test;
  test.depths = ctx.storageBufferIndex(buffer);
  test.rowStride = rowStride;
  // The attachment's comparison, done by the shader: VkCompareOp's values are its pass bits.
  test.compareOp = static_cast<uint32_t>(kDepthCompare);
  return test;
}

namespace {

// The depth attachment of a forward pass: the first pass using depth clears it.
void attachDepth(graph::NodeBuilder& node, FrameTargets& targets, const graph::ClearValue& clear, bool writesDepth) {
  if (!targets.depthCleared)
    targets.depth = node.setDepthStencil(targets.depth, graph::LoadOp::Clear, clear);
  else if (writesDepth)
    targets.depth = node.setDepthStencil(targets.depth, graph::LoadOp::Load);
  else
    node.setDepthStencilReadOnly(targets.depth);
  targets.depthCleared = true;
}

}  // namespace

graph::NodeBuilder addForwardPass(graph::FrameGraph& graph, FrameTargets& targets, std::string_view name,
                                  bool writesDepth, DepthTest depthTest) {
  if (targets.colorResolved) {
    throw std::logic_error(
        "colour pass '" + std::string(name) +
        "' declared after the MSAA resolve: the render path must compose it before MsaaResolveFeature");
  }
  if (depthTest == DepthTest::OpaqueDepthBuffer && writesDepth)
    throw std::logic_error("colour pass '" + std::string(name) + "' writes depth: it needs DepthTest::Attachment");
  auto node = graph.addNode(name, graph::NodeType::Graphics);
  const graph::LoadOp load = targets.colorCleared ? graph::LoadOp::Load : graph::LoadOp::Clear;
  const graph::ClearValue clear{targets.background, kDepthClear, 0};
  targets.color = node.addColorTarget(targets.color, load, clear);
  // Single-sampled, the HDR image is the colour target itself; multisampled, "MSAA Resolve" writes it.
  if (targets.samples == 1) targets.hdr = targets.color;
  targets.colorCleared = true;

  if (depthTest == DepthTest::Attachment) {
    attachDepth(node, targets, clear, writesDepth);
  } else if (targets.opaqueDepth.valid()) {
    // The fragment shader reads it; the vertex shaders read other buffers through the same
    // read-only binding, which the node's descriptor set exposes this buffer in, so (as for
    // every buffer a forward pass reads) synchronization validation counts a vertex read too.
    node.read(targets.opaqueDepth, graph::Access::StorageRead, graph::kStageVertexShader | graph::kStageFragmentShader);
  }
  // Every colour pass pre-exposes what it writes (forward: fragment stage; particles: vertex).
  if (targets.exposure.valid())
    node.read(targets.exposure, graph::Access::StorageRead, graph::kStageVertexShader | graph::kStageFragmentShader);
  return node;
}

OpaqueDepthSource opaqueDepthSource(const FrameTargets& targets, DepthTest depthTest) {
  if (depthTest == DepthTest::Attachment) return {};
  return {targets.opaqueDepth, targets.extent.width};
}

rhi::BufferId createReadbackBuffer(rhi::Device& device, const std::string& name, uint64_t bytes) {
  const rhi::BufferId buffer = device.createBuffer({name, bytes, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  std::memset(device.mapped(buffer).data(), 0, bytes);
  return buffer;
}

void declareReadback(graph::FrameGraph& graph, std::string_view nodeName, graph::BufferHandle source,
                     rhi::BufferId readback, std::string_view name, uint64_t bytes) {
  const graph::ImportState hostState{graph::kStageHost | graph::kStageTransfer,
                                     graph::kAccessHostRead | graph::kAccessTransferWrite, graph::Layout::Undefined,
                                     graph::QueueClass::Graphics};
  auto target = graph.importBuffer(name, {bytes, {}}, rhi::external(readback), hostState, hostState);
  auto node = graph.addNode(nodeName, graph::NodeType::Transfer);
  node.read(source, graph::Access::TransferSrc);
  target = node.write(target, graph::Access::TransferDst);
  node.sideEffect();
  node.setJob([source, target, bytes](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().copyBuffer(ctx.buffer(source), ctx.buffer(target), bytes);
  });
  node.recordingFixed();
}

}  // namespace fgb::features
