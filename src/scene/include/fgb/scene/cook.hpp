// Cooking: turns an assembled scene into its GPU-ready form. Per mesh: vertex-cache optimisation
// (Forsyth-style, meshoptimizer) then vertex-fetch reordering, clusters of at most 128 triangles
// with bounds and normal cones (meshopt_buildMeshlets) and their LOD DAG (cluster_lod.hpp), and
// fresh local/world bounds.
// Textures already carry their mip chains (makeTexture). Materials get a default when none exist.
#pragma once

#include <fgb/scene/scene.hpp>

#include <cstdint>

namespace fgb::scene {

// Bump when the cooked output of the same input changes: it is part of every cache key.
// 2: world placement in double; 3: stress-nan lights; 4: clusters (meshopt_buildMeshlets);
// 5: clusters as vertex lists + packed 8-bit local triangles; 6: the cluster LOD DAG; 7: its
// errors at least 2% of the group's radius; 8: and at least half its normal spread
inline constexpr uint32_t kCookerVersion = 8;

void cookScene(Scene& scene);

}  // namespace fgb::scene
