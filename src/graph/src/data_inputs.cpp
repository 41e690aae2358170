#include <algorithm>
#include <fgb/graph/data_inputs.hpp>

namespace fgb::graph {

std::vector<std::vector<uint32_t>> dataInputs(const FrameGraph& graph) {
  const auto nodeCount = uint32_t(graph.nodes().size());
  // Versions are numbered graph-wide; a version's writer is the node whose access created it.
  std::vector<uint32_t> writer;
  for (uint32_t node = 0; node < nodeCount; ++node) {
    for (const ResourceAccess& use : graph.accesses(node)) {
      if (use.writeVersion == kInvalidIndex) continue;
      if (writer.size() <= use.writeVersion) writer.resize(use.writeVersion + 1, kInvalidIndex);
      writer[use.writeVersion] = node;
    }
  }
  std::vector<std::vector<uint32_t>> inputs(nodeCount);
  for (uint32_t node = 0; node < nodeCount; ++node) {
    for (const ResourceAccess& use : graph.accesses(node)) {
      if (use.readVersion == kInvalidIndex || use.readVersion >= writer.size()) continue;
      const uint32_t from = writer[use.readVersion];
      if (from != kInvalidIndex && from != node) inputs[node].push_back(from);
    }
    std::sort(inputs[node].begin(), inputs[node].end());
    inputs[node].erase(std::unique(inputs[node].begin(), inputs[node].end()), inputs[node].end());
  }
  return inputs;
}

}  // namespace fgb::graph
