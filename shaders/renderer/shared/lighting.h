// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): push blocks and sizes of clustered lighting
// (src/renderer/features/lighting/; cluster_bounds.comp, light_cull.comp).
#ifndef FGB_RENDERER_SHARED_LIGHTING_H
#define FGB_RENDERER_SHARED_LIGHTING_H

#include "fgb/rhi/shared/prelude.h"

#define FGB_CLUSTER_BOUNDS_GROUP_SIZE 64  // cluster_bounds.comp: one cluster each
#define FGB_LIGHT_CULL_STATS \
  4  // a workgroup's row: lights found in all its clusters, most in one, clusters over capacity, 0
#define FGB_LIGHT_CULL_BLOCK 8            // light_cull.comp: one workgroup per 8x8 tiles of a slice
#define FGB_MAX_LIGHTS_PER_CLUSTER 1024   // the largest lighting.max_per_cluster light_cull.comp keeps

FGB_GPU_BEGIN

// cluster_bounds.comp.
struct ClusterBoundsPush {
  uint frame;
  uint bounds;  // vec4 pairs: min, max per cluster
  uint clusterCount;
};
FGB_CHECK_PUSH(ClusterBoundsPush, 12)

// light_cull.comp.
struct LightCullPush {
  uint frame;
  uint bounds;
  uint lights;
  uint counts;   // per cluster: lights found (may exceed the capacity: overflow is visible)
  uint indices;  // cluster c's lights at [c * capacity, c * capacity + min(count, capacity))
  uint dropLight;  // debug.drop_light: K >= 1 leaves light K - 1 out of every cluster; 0: none
  uint statsToHost;  // per workgroup a row of FGB_LIGHT_CULL_STATS uints in host memory (statistics)
  uint pad;
};
FGB_CHECK_PUSH(LightCullPush, 32)

FGB_GPU_END

#endif
