#include "pass_capture_feature.hpp"

#include <algorithm>
#include <cstring>
#include <map>

#include "../visbuffer/visbuffer_feature.hpp"

namespace fgb::features {
namespace {

using graph::Access;

// A texture's size as the compiler will resolve it (dependent extents follow extentFrom).
graph::Extent extentOf(const graph::FrameGraph& graph, uint32_t resource) {
  const graph::TextureDesc& desc = graph.resources()[resource].texture;
  if (!desc.extentFrom.valid()) return desc.extent;
  const graph::Extent base = extentOf(graph, graph.resourceOf(desc.extentFrom));
  return {std::max(1u, base.width >> desc.extentShift), std::max(1u, base.height >> desc.extentShift), 1};
}

// Buffers that hold images of the scene passes' size: the visibility-buffer path's opaque depth
// (float per pixel) and visibility words (uint64 per pixel, buffer backing), by resource index.
std::map<uint32_t, CapturedContent> imageBuffers(const graph::FrameGraph& graph, const Blackboard& board) {
  std::map<uint32_t, CapturedContent> buffers;
  if (const auto* targets = board.find<FrameTargets>(); targets && targets->opaqueDepth.valid())
    buffers[graph.resourceOf(targets->opaqueDepth)] = CapturedContent::Depth;
  if (const auto* vis = board.find<VisibilityOutputs>(); vis && vis->visibility.valid())
    buffers[graph.resourceOf(vis->visibility)] = CapturedContent::Visibility;
  return buffers;
}

// Nodes the harness adds to inspect others are never captured themselves.
bool isInspection(const std::string& name) {
  return name.rfind("Finite Check", 0) == 0;
}

}  // namespace

bool capturableFormat(graph::Format format) {
  switch (format) {
    case graph::Format::R8G8B8A8Unorm:
    case graph::Format::R8G8B8A8Srgb:
    case graph::Format::R16G16B16A16Sfloat:
    case graph::Format::R32G32B32A32Sfloat:
    case graph::Format::R16G16Sfloat:
    case graph::Format::R32Sfloat:
    case graph::Format::D32Sfloat:
      return true;
    default:
      return false;
  }
}

void PassCaptureFeature::initialize(FeatureInit& init) {
  enabled_ = init.settings.capture;
  device_ = &init.device;
  sceneExtent_ = {init.settings.sceneWidth(), init.settings.sceneHeight(), 1};
}

std::vector<PassCaptureFeature::Target> PassCaptureFeature::targetsOf(const graph::FrameGraph& graph, uint32_t node,
                                                                      const Blackboard& board) const {
  const auto buffers = imageBuffers(graph, board);
  // The last version of each resource the node wrote: what the nodes after it read.
  std::map<uint32_t, Target> last;
  for (const graph::ResourceAccess& use : graph.accesses(node)) {
    if (use.writeVersion == graph::kInvalidIndex) continue;
    const graph::ResourceDecl& resource = graph.resources()[use.resource];
    Target target;
    target.resource = resource.name;
    if (resource.kind == graph::ResourceKind::Texture) {
      const graph::TextureDesc& desc = resource.texture;
      if (desc.samples != 1 || !capturableFormat(desc.format)) continue;
      target.texture = {use.writeVersion};
      target.format = desc.format;
      target.extent = extentOf(graph, use.resource);
      target.content = graph::isDepthFormat(desc.format) ? CapturedContent::Depth : CapturedContent::Color;
      target.bytes = uint64_t{target.extent.width} * target.extent.height * graph::bytesPerPixel(desc.format);
    } else {
      const auto found = buffers.find(use.resource);
      if (found == buffers.end()) continue;
      target.buffer = {use.writeVersion};
      target.content = found->second;
      target.extent = sceneExtent_;
      target.bytes =
          uint64_t{sceneExtent_.width} * sceneExtent_.height * (found->second == CapturedContent::Visibility ? 8u : 4u);
    }
    last[use.resource] = std::move(target);
  }
  std::vector<Target> targets;
  uint64_t offset = 0;
  for (auto& [resource, target] : last) {
    target.offset = offset;
    offset += (target.bytes + 255) & ~uint64_t{255};  // copy offsets aligned for every texel size
    targets.push_back(std::move(target));
  }
  return targets;
}

void PassCaptureFeature::declareCopy(graph::FrameGraph& graph, Captured& captured) {
  uint64_t bytes = 0;
  for (const Target& target : captured.targets) bytes = std::max(bytes, target.offset + target.bytes);
  captured.readback = device_->createBuffer(
      {"capture readback: " + captured.pass, bytes, rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  const graph::ImportState hostState{graph::kStageHost | graph::kStageTransfer,
                                     graph::kAccessHostRead | graph::kAccessTransferWrite, graph::Layout::Undefined,
                                     graph::QueueClass::Graphics};
  auto readback = graph.importBuffer("capture readback: " + captured.pass, {bytes, {}},
                                     rhi::external(captured.readback), hostState, hostState);
  // On the graphics queue, like the finite check: the textures stay on the queue that wrote them
  // or are acquired like any other read.
  auto node = graph.addNode("Capture: " + captured.pass, graph::NodeType::Transfer, graph::QueueClass::Graphics);
  for (const Target& target : captured.targets) {
    if (target.texture.valid())
      node.read(target.texture, Access::TransferSrc);
    else
      node.read(target.buffer, Access::TransferSrc);
  }
  readback = node.write(readback, Access::TransferDst);
  node.sideEffect();
  node.setJob([targets = captured.targets, readback](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    for (const Target& target : targets) {
      if (target.texture.valid()) {
        ctx.cmd().copyTextureToBuffer(ctx.texture(target.texture), ctx.buffer(readback), target.offset);
      } else {
        const rhi::BufferCopy region{0, target.offset, target.bytes};
        ctx.cmd().copyBuffer(ctx.buffer(target.buffer), ctx.buffer(readback), std::span(&region, 1));
      }
    }
  });
  node.recordingFixed();
}

void PassCaptureFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled_) return;
  captured_.clear();  // declared again when the workload recompiles its graph (one queue, and back)
  const auto wanted = [&](const std::string& name) {
    return wanted_.empty() || std::find(wanted_.begin(), wanted_.end(), name) != wanted_.end();
  };
  const auto declared = uint32_t(graph.nodes().size());  // not the capture nodes added below
  for (uint32_t node = 0; node < declared; ++node) {
    const std::string name = graph.nodes()[node].name;
    if (isInspection(name) || !wanted(name)) continue;
    Captured captured{name, targetsOf(graph, node, board), {}};
    if (captured.targets.empty()) continue;
    declareCopy(graph, captured);
    captured_.push_back(std::move(captured));
  }
}

std::vector<CapturedBytes> PassCaptureFeature::read() const {
  std::vector<CapturedBytes> result;
  for (const Captured& captured : captured_) {
    const auto mapped = device_->mapped(captured.readback);
    for (const Target& target : captured.targets) {
      CapturedBytes out{captured.pass, target.resource, target.content, target.format, target.extent, {}};
      out.bytes.resize(target.bytes);
      std::memcpy(out.bytes.data(), mapped.data() + target.offset, target.bytes);
      result.push_back(std::move(out));
    }
  }
  return result;
}

}  // namespace fgb::features
