// Which nodes feed which: the read-after-write edges of a declaration, the graph's own data flow.
// Per-pass goldens use it to find where a difference enters the frame (a node whose output
// differs while every node it reads from matches). Pure: no Vulkan, no compilation needed.
#pragma once

#include <cstdint>
#include <fgb/graph/frame_graph.hpp>
#include <vector>

namespace fgb::graph {

// Per declared node, ascending: the nodes that wrote a version it reads (a sampled/storage read,
// or the previous contents a write loads, e.g. a colour attachment loaded from an earlier pass).
// Write-after-read and queue-order edges are not data and are left out; so are versions created
// with their resource (imports, which no node wrote).
std::vector<std::vector<uint32_t>> dataInputs(const FrameGraph& graph);

}  // namespace fgb::graph
