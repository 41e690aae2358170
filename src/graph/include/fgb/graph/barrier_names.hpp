// Barriers in words for the Graphviz dump: stages, accesses and layouts by name ("compute",
// "storage-write", "shader-read-only") instead of the bit values, so a reader needs no header.
#pragma once

#include <fgb/graph/compiled_graph.hpp>
#include <fgb/graph/types.hpp>
#include <string>
#include <string_view>

namespace fgb::graph {

std::string stageNames(StageMask stages);    // "early-fragment-tests+late-fragment-tests"; "none" for 0
std::string accessNames(AccessMask access);  // "storage-write+sampled-read"; "none" for 0
std::string_view layoutName(Layout layout);  // "shader-read-only"

// "hdr: compute → fragment, storage-write → sampled-read, general → shader-read-only" (the layout
// part for textures only), preceded by "release "/"acquire " and followed by "queue 1 → 0" for an
// ownership transfer. `resourceName` and `isTexture` come from the graph's declaration.
std::string describeBarrier(const Barrier& barrier, std::string_view resourceName, bool isTexture);

}  // namespace fgb::graph
