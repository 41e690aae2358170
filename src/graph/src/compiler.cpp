// The compiler pipeline. Each stage lives in stage_*.cpp and reads/writes CompileState; the order
// below is the only place that knows the sequence.
#include "compile_state.hpp"

#include <string>

namespace fgb::graph {

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
  out.queueCount = options.queueCount;
  detail::CompileState state(graph, options, out);
  detail::assignQueues(state);
  detail::cullNodes(state);
  // With nothing culled, the level sort sees every node and reports cycles itself; otherwise a
  // cycle through culled nodes would go unseen there, so check the whole declaration first.
  if (state.anyCulled) detail::detectCycles(state);
  detail::buildDependencies(state);
  detail::sortByLevel(state);
  detail::pruneCrossQueueEdges(state);
  detail::placeSubmits(state);
  detail::resolveResources(state);
  detail::computeLifetimes(state);
  detail::placeTransients(state);
  detail::planBarriers(state);
  return out;
}

}  // namespace fgb::graph
