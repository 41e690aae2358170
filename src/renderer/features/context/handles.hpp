// Graph handles features publish on the blackboard for each other.
#pragma once

#include <fgb/graph/frame_graph.hpp>

namespace fgb::features {

// Published by the clustered lighting feature ("Clustered Light Cull"): per-cluster light counts
// and fixed-capacity index lists (cluster c's lights start at c * maxLightsPerCluster).
struct ClusteredLights {
  graph::BufferHandle counts;
  graph::BufferHandle indices;
};

// Published by the bloom feature: the texture tone mapping adds (scaled by the bloom intensity).
struct BloomOutput {
  graph::TextureHandle texture;
};

}  // namespace fgb::features
