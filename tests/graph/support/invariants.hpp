// Independent invariant checks of a CompiledGraph against the GraphModel and the brute-force
// Reference. Each returns a list of human-readable problems (empty = holds), so a property test
// can print the seed and every violated fact at once.
#pragma once

#include "graph_model.hpp"
#include "reference.hpp"

#include <fgb/graph/compiler.hpp>

#include <string>
#include <vector>

namespace fgb::graph::test {

using Problems = std::vector<std::string>;

// Execution order of the compiled plan: same queue = step order; across queues = a chain of
// timeline-semaphore waits between submits (a wait on value v covers every earlier submit too).
class HappensBefore {
 public:
  explicit HappensBefore(const CompiledGraph& compiled);
  // True when everything `before` does completes before `after` starts (nodes, not steps).
  [[nodiscard]] bool ordered(uint32_t before, uint32_t after) const;
  [[nodiscard]] bool submitsAcyclic() const { return acyclic_; }

 private:
  const CompiledGraph* compiled_;
  std::vector<std::vector<char>> submitReach_;
  bool acyclic_ = true;
};

Problems checkDeclaration(const GraphModel& expected, const FrameGraph& graph);
Problems checkCulling(const GraphModel& model, const FrameGraph& graph, const Reference& ref,
                      const CompiledGraph& compiled);
Problems checkOrderAndLevels(const GraphModel& model, const Reference& ref, const CompiledGraph& compiled);
Problems checkQueuesAndSync(const GraphModel& model, const Reference& ref, const CompiledGraph& compiled,
                            const CompileOptions& options);
Problems checkSubmits(const Reference& ref, const CompiledGraph& compiled);
Problems checkLifetimes(const GraphModel& model, const CompiledGraph& compiled);
Problems checkAliasing(const GraphModel& model, const FrameGraph& graph, const CompiledGraph& compiled,
                       const CompileOptions& options);
Problems checkResolvedFields(const FrameGraph& graph, const CompiledGraph& compiled);
Problems checkBarriers(const GraphModel& model, const FrameGraph& graph, const Reference& ref,
                       const CompiledGraph& compiled, const CompileOptions& options);

// Every check above, in pipeline order.
Problems checkEverything(const GraphModel& model, const FrameGraph& graph, const Reference& ref,
                         const CompiledGraph& compiled, const CompileOptions& options);

std::string joinProblems(const Problems& problems, size_t limit = 12);

}  // namespace fgb::graph::test
