#include "graph_model.hpp"

namespace fgb::graph::test {
namespace {

// Chain position of a version: how many writes separate it from the resource's first version.
int chainPosition(const FrameGraph& graph, uint32_t version) {
  int position = 0;
  for (uint32_t v = version; versionsOf(graph)[v].previous != kInvalidIndex; v = versionsOf(graph)[v].previous) {
    ++position;
  }
  return position;
}

}  // namespace

GraphModel modelFromGraph(const FrameGraph& graph) {
  GraphModel model;
  for (const ResourceDecl& resource : graph.resources()) {
    model.resourceName.emplace_back(resource.name);
    model.kind.push_back(resource.kind);
    model.imported.push_back(resource.imported);
  }
  for (uint32_t node = 0; node < graph.nodes().size(); ++node) {
    const NodeDecl& decl = graph.nodes()[node];
    model.nodeName.emplace_back(decl.name);
    model.nodeType.push_back(decl.type);
    model.nodeClass.push_back(decl.queue);
    model.sideEffect.push_back(decl.sideEffect);
    for (const Use& use : usesOf(graph, node)) {
      ModelUse modelUse{.node = node, .resource = use.resource, .access = use.access,
                        .shaderStages = use.shaderStages};
      if (use.readVersion != kInvalidIndex) modelUse.readPos = chainPosition(graph, use.readVersion);
      if (use.writeVersion != kInvalidIndex) modelUse.writePos = chainPosition(graph, use.writeVersion);
      model.uses.push_back(modelUse);
    }
  }
  return model;
}

std::array<uint32_t, kQueueClassCount> queueOfClassFor(uint32_t queueCount) {
  switch (queueCount) {
    case 1: return {0, 0, 0};
    case 2: return {0, 1, 1};
    default: return {0, 1, 2};
  }
}

}  // namespace fgb::graph::test
