// The compiler pipeline. Each stage lives in stage_*.cpp and reads/writes CompileState; the order
// below is the only place that knows the sequence.
#include "compile_state.hpp"

#include <chrono>
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

// Runs the stages in order, timing each when a profile was asked for.
class StageRunner {
 public:
  StageRunner(detail::CompileState& state, CompileProfile* profile) : state_(state), profile_(profile) {
    if (profile_ != nullptr) {
      ++profile_->compiles;
      last_ = Clock::now();
    }
  }
  void run(CompileStage stage, void (*function)(detail::CompileState&)) {
    function(state_);
    if (profile_ == nullptr) return;
    const Clock::time_point now = Clock::now();
    profile_->microseconds[static_cast<size_t>(stage)] += std::chrono::duration<double, std::micro>(now - last_).count();
    last_ = now;
  }

 private:
  using Clock = std::chrono::steady_clock;
  detail::CompileState& state_;
  CompileProfile* profile_;
  Clock::time_point last_{};
};

}  // namespace

const char* toString(CompileStage stage) {
  static constexpr const char* kNames[] = {"resources", "cull",      "dependencies", "sort",
                                           "ssis",      "submits",   "barriers"};
  static_assert(std::size(kNames) == static_cast<size_t>(CompileStage::Count));
  const auto index = static_cast<size_t>(stage);
  return index < std::size(kNames) ? kNames[index] : "?";
}

CompiledGraph::~CompiledGraph() {
  // Node infos and submits go back with their elements: the next compile's resize constructs
  // none, and wait lists keep their capacity. The stages that fill them overwrite every element.
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
  StageRunner stages(state, options.profile);
  stages.run(CompileStage::Resources, detail::resolveResources);
  stages.run(CompileStage::Cull, detail::cullNodes);
  // Also detects cycles: over every declared node, so one through culled nodes is reported too.
  stages.run(CompileStage::Dependencies, detail::buildDependencies);
  stages.run(CompileStage::Sort, detail::sortByLevel);
  stages.run(CompileStage::Ssis, detail::pruneCrossQueueEdges);
  stages.run(CompileStage::Submits, detail::placeSubmits);
  stages.run(CompileStage::Barriers, detail::placeAndPlanBarriers);
  return out;
}

}  // namespace fgb::graph
