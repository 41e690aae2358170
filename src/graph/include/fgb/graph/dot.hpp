// Graphviz dumps of a compiled graph. Brief: nodes and resource flow. Full: plus resource
// parameters, usages, barriers, queues, submit boundaries, aliasing slots; culled nodes dashed with
// the reason. Both are accepted by `dot -Tsvg`.
#pragma once

#include <fgb/graph/compiled_graph.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <string>

namespace fgb::graph {

enum class DotDetail : uint8_t { Brief, Full };

std::string toDot(const FrameGraph& graph, const CompiledGraph& compiled, DotDetail detail);

}  // namespace fgb::graph
