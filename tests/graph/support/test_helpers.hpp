// Small builders shared by the hand-written unit tests.
#pragma once

#include "graph_model.hpp"
#include "invariants.hpp"
#include "reference.hpp"

#include <fgb/graph/compiler.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <utility>

namespace fgb::graph::test {

inline TextureDesc colorDesc(uint32_t width = 256, uint32_t height = 256,
                             Format format = Format::R16G16B16A16Sfloat) {
  TextureDesc desc;
  desc.format = format;
  desc.extent = {width, height, 1};
  return desc;
}

inline BufferDesc bufferDesc(uint64_t size = 4096) {
  BufferDesc desc;
  desc.size = size;
  return desc;
}

// An imported colour texture that leaves the graph sampled (e.g. a swapchain-like output).
inline TextureHandle importOutput(FrameGraph& graph, std::string_view name) {
  return graph.importTexture(name, colorDesc(), {7}, ImportState{.layout = Layout::Undefined},
                             ImportState{.layout = Layout::ShaderReadOnly});
}

inline CompileOptions queueOptions(uint32_t queues) {
  CompileOptions options;
  options.queueCount = queues;
  options.queueOfClass = queueOfClassFor(queues);
  return options;
}

inline uint32_t nodeNamed(const FrameGraph& graph, std::string_view name) {
  for (uint32_t n = 0; n < graph.nodes().size(); ++n) {
    if (graph.nodes()[n].name == name) return n;
  }
  ADD_FAILURE() << "no node named " << name;
  return 0;
}

inline uint32_t resourceNamed(const FrameGraph& graph, std::string_view name) {
  for (uint32_t r = 0; r < graph.resources().size(); ++r) {
    if (graph.resources()[r].name == name) return r;
  }
  ADD_FAILURE() << "no resource named " << name;
  return 0;
}

using NamePairs = std::set<std::pair<std::string, std::string>>;

inline NamePairs edgeNames(const FrameGraph& graph, const std::vector<Edge>& edges) {
  NamePairs names;
  for (const Edge& e : edges) names.emplace(graph.nodes()[e.from].name, graph.nodes()[e.to].name);
  return names;
}

// Runs every brute-force invariant on a hand-written graph as well (belt and braces).
inline void expectAllInvariants(const FrameGraph& graph, const CompiledGraph& compiled,
                                const CompileOptions& options) {
  const GraphModel model = modelFromGraph(graph);
  const Reference ref = computeReference(model, options.cull);
  const Problems problems = checkEverything(model, graph, ref, compiled, options);
  EXPECT_TRUE(problems.empty()) << joinProblems(problems);
}

// Barriers on `resource` recorded before (or after) the step of `node`.
inline std::vector<Barrier> barriersAround(const CompiledGraph& compiled, uint32_t node, uint32_t resource,
                                           bool before) {
  const Step& step = compiled.steps[compiled.nodes[node].step];
  const BarrierRange range = before ? step.before : step.after;
  std::vector<Barrier> found;
  for (uint32_t b = range.first; b < range.first + range.count; ++b) {
    if (compiled.barriers[b].resource == resource) found.push_back(compiled.barriers[b]);
  }
  return found;
}

}  // namespace fgb::graph::test
