// The compiler pipeline. Each stage lives in stage_*.cpp and reads/writes CompileState; the order
// below is the only place that knows the sequence.
#include <chrono>
#include <string>

#include "compile_state.hpp"

namespace fgb::graph {

const char* toString(CompileStage stage) {
  static constexpr const char* kNames[] = {"resources", "cull", "dependencies", "sort", "ssis", "submits", "barriers"};
  static_assert(std::size(kNames) == static_cast<size_t>(CompileStage::Count));
  const auto index = static_cast<size_t>(stage);
  return index < std::size(kNames) ? kNames[index] : "?";
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
  out.queueCount = options.queueCount;
  detail::CompileState state(graph, options, out);
  // Runs one stage; with a profile, adds the stage's wall time to it (without one, reads no clock).
  using Clock = std::chrono::steady_clock;
  Clock::time_point last = options.profile != nullptr ? Clock::now() : Clock::time_point{};
  if (options.profile != nullptr) ++options.profile->compiles;
  auto run = [&](CompileStage stage, void (*function)(detail::CompileState&)) {
    function(state);
    if (options.profile == nullptr) return;
    const Clock::time_point now = Clock::now();
    options.profile->microseconds[static_cast<size_t>(stage)] +=
        std::chrono::duration<double, std::micro>(now - last).count();
    last = now;
  };
  run(CompileStage::Resources, detail::resolveResources);
  // Culling first: the dependency stage then orders only alive nodes. It still detects cycles over
  // every declared node, so that one through culled nodes is reported too.
  run(CompileStage::Cull, detail::cullNodes);
  run(CompileStage::Dependencies, detail::buildDependencies);
  run(CompileStage::Sort, detail::sortByLevel);
  run(CompileStage::Ssis, detail::pruneCrossQueueEdges);
  run(CompileStage::Submits, detail::placeSubmits);
  run(CompileStage::Barriers, detail::placeAndPlanBarriers);
  return out;
}

}  // namespace fgb::graph
