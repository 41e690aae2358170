// The compiler pipeline. Each stage lives in stage_*.cpp and reads/writes CompileState; the order
// below is the only place that knows the sequence.
#include "compile_state.hpp"

#include <string>
#include <type_traits>

namespace fgb::graph {
namespace {

// Calls `each` on every array of a CompiledGraph.
template <typename Each>
void forEachArray(CompiledGraph& graph, Each&& each) {
  each(graph.nodes);
  each(graph.order);
  each(graph.edges);
  each(graph.syncEdges);
  each(graph.steps);
  each(graph.barriers);
  each(graph.submits);
  each(graph.submitsPerQueue);
  each(graph.resources);
  each(graph.resourceAlive);
  each(graph.lifetimes);
  each(graph.aliasing.placements);
  each(graph.aliasing.heaps);
}

template <typename Vector>
using PoolOf = detail::VectorPool<typename std::remove_reference_t<Vector>::value_type>;

}  // namespace

CompiledGraph::~CompiledGraph() {
  // Node infos and submits go back with their elements, so that diagnostics and wait lists keep
  // their capacity too; the stages that fill them overwrite every element they keep.
  detail::VectorPool<NodeInfo>::give(nodes, detail::VectorPool<NodeInfo>::Keep::Elements);
  detail::VectorPool<Submit>::give(submits, detail::VectorPool<Submit>::Keep::Elements);
  forEachArray(*this, [](auto& array) { PoolOf<decltype(array)>::give(array); });
}

CompiledGraph compile(const FrameGraph& graph, const CompileOptions& options) {
  if (options.queueCount < 1 || options.queueCount > kQueueClassCount) {
    throw GraphError("compile: queueCount must be 1.." + std::to_string(kQueueClassCount) + ", got " +
                     std::to_string(options.queueCount));
  }
  for (uint32_t queue : options.queueOfClass) {
    if (queue >= options.queueCount) {
      throw GraphError("compile: queueOfClass maps a queue class to queue " + std::to_string(queue) +
                       " but queueCount is " + std::to_string(options.queueCount));
    }
  }
  CompiledGraph out;
  forEachArray(out, [](auto& array) { PoolOf<decltype(array)>::take(array); });
  out.queueCount = options.queueCount;
  detail::CompileState state(graph, options, out);
  detail::resolveResources(state);
  detail::cullNodes(state);
  // Also detects cycles: over every declared node, so one through culled nodes is reported too.
  detail::buildDependencies(state);
  detail::sortByLevel(state);
  detail::pruneCrossQueueEdges(state);
  detail::placeSubmits(state);
  detail::computeLifetimes(state);
  detail::placeAndPlanBarriers(state);
  return out;
}

}  // namespace fgb::graph
