#include "msaa_resolve_feature.hpp"

namespace fgb::features {
namespace {

// Colour attachment loaded, resolve attachment written at the end of the render pass; the executor
// begins rendering for a graphics node with attachments even though its job records nothing.
void declareResolve(graph::FrameGraph& graph, FrameTargets& targets) {
  auto node = graph.addNode("MSAA Resolve", graph::NodeType::Graphics);
  graph::TextureHandle samples;
  targets.hdr = node.addColorTargetWithResolve(targets.color, targets.hdr, &samples, graph::LoadOp::Load);
  targets.color = samples;
  node.setJob([](graph::JobContext&) {}).recordingFixed();
}

}  // namespace

void MsaaResolveFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  auto& targets = board.get<FrameTargets>();
  if (targets.colorResolved) throw std::logic_error("MSAA Resolve declared twice");
  if (!targets.colorCleared)
    addForwardPass(graph, targets, "Clear", true).setJob([](graph::JobContext&) {}).recordingFixed();
  if (targets.samples > 1) declareResolve(graph, targets);
  targets.colorResolved = true;
}

}  // namespace fgb::features
