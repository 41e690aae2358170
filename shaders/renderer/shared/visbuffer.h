// Shared by C++ and GLSL (fgb/rhi/shared/prelude.h): the visibility-buffer path's GPU structs,
// push blocks, flags and sizes (src/renderer/features/visbuffer/, shaders/renderer/visbuffer/).
// GLSL: VisCounters needs GL_EXT_shader_explicit_arithmetic_types_int64 (visbuffer.glsl).
#ifndef FGB_RENDERER_SHARED_VISBUFFER_H
#define FGB_RENDERER_SHARED_VISBUFFER_H

#include "fgb/rhi/shared/prelude.h"
#include "renderer/shared/debug.h"

// Workgroup sizes (local_size_x/y of the shaders; the feature dispatches with them).
#define FGB_VIS_CULL_GROUP_SIZE 64    // cluster_cull.comp, cluster_cull_late.comp: one cluster each
#define FGB_VIS_RASTER_GROUP_SIZE 64  // visibility_raster.comp: small triangles per workgroup
#define FGB_VIS_SHADE_GROUP_SIZE 8    // material_shade.comp: 8 x 8 pixels
#define FGB_VIS_CLEAR_GROUP_SIZE 8    // vis_clear.comp: 8 x 8 pixels
#define FGB_HIZ_GROUP_SIZE 256        // hiz_build.comp: threads of a workgroup, which reduces one tile
// hiz_build.comp: the levels one dispatch writes; a workgroup reduces a tile of 2^6 x 2^6 texels of
// the level it reads through shared memory (hizPassGroups in hiz_occlusion.glsl sizes the dispatches).
#define FGB_HIZ_PASS_LEVELS 6

FGB_GPU_BEGIN

// Cluster draw flags (ClusterDraw::flags).
const uint kClusterSingleSided = 1u;  // back faces are culled (glTF: not double-sided)
const uint kClusterMirrored = 2u;     // negative determinant: front faces wind the other way on screen
const uint kClusterConeUsable = 4u;   // near-uniform scale: the cluster's normal cone stays valid in world space
const uint kClusterAlphaMasked = 8u;  // alpha-tested during "Visibility Raster"

// scene::Cluster as the shaders read it (the upload copies the scene's clusters as they are:
// gpu_upload.cpp checks the layouts agree). A cluster's triangles are packed words
// (scene::packClusterTriangle: three 8-bit indices into the cluster's vertex list); its vertices are
// firstVertex + those indices in the scene-wide cluster vertex stream (ClusterGeometry::vertices:
// position, attribute vertex).
// The LOD fields are scene::Cluster's: the group that made the cluster and the group it is a
// member of (mesh-local spheres and errors, monotonic up the DAG; "Cluster Cull" keeps a cluster
// whose own error projects to at most render.lod_error pixels and whose parent's projects to more).
struct ClusterData {
  vec4 sphere;  // mesh-local centre, radius
  vec4 cone;    // mesh-local axis, cutoff
  uint firstTriangle;
  uint triangleCount;
  uint firstVertex;
  uint vertexCount;
  vec4 lodSphere;     // the group that made it (its own sphere at level 0)
  vec4 parentSphere;  // the group it is a member of
  float lodError;     // 0 at level 0
  float parentError;  // scene::kLodRootError for a root
  uint lodLevel;
  uint pad;
};
FGB_CHECK_SIZE(ClusterData, 96)

// Clusters drawn per LOD level are counted up to this level (higher levels count in the last).
#define FGB_VIS_LOD_STAT_LEVELS 8

// One cluster of one instance (what "Cluster Cull" tests).
struct ClusterDraw {
  uint instance;     // GPU instance index
  uint cluster;      // index into the scene's clusters
  uint firstVertex;  // the mesh's first vertex (cluster indices are mesh-local)
  uint flags;        // kCluster* bits
};
FGB_CHECK_SIZE(ClusterDraw, 16)

// Counters and indirect dispatch arguments written by the culling nodes.
struct VisCounters {
  uint visibleClusters;
  uint filterGroups[3];   // "Triangle Filter": one workgroup per visible cluster
  uint smallTriangles;
  uint smallGroups[3];    // "Visibility Raster", small triangles: one thread each
  uint64_t largeTotals;   // high 24 bits: large triangles, low 40 bits: their tile jobs
  uint largeTriangles;
  uint tileJobs;          // jobs of at most 16 8x8 tiles of one large triangle (capped by the list)
  uint tileGroups[3];     // "Visibility Raster", large triangles: one workgroup per tile job
  uint overflow;          // large triangles dropped for lack of list space (should stay 0)
  // render.occlusion=1 (two-phase HiZ culling). The phase-2 ("late") nodes count in counters of
  // their own, whose visible clusters follow phase 1's in the visible-cluster list:
  uint firstCluster;      // the list slot of this phase's first cluster (0 in phase 1)
  uint occluded;          // phase 1: clusters held back by last frame's HiZ (phase 2 re-tests them)
  uint reserved[2];
  uint lodClusters[FGB_VIS_LOD_STAT_LEVELS];  // visible clusters per LOD level (statistics)
};
FGB_CHECK_SIZE(VisCounters, 112)
const uint kVisCounterWords = 28u;  // sizeof(VisCounters) / 4: "Material Shade" copies them word by word

// "Cluster Cull" (cluster_cull.comp).
// Storage-buffer indices fit 16 bits (FGB_MAX_STORAGE_BUFFERS), so pairs share a word, which
// leaves room in 128 bytes for the LOD threshold.
struct ClusterCullPush {
  uint frame;      // FrameConstants: the frustum planes, kFrameHizValid
  uint instances;
  uint draws;
  uint clusters;
  uint counters;
  uint visible;    // visible-cluster list: ClusterDraw indices
  uint occlusion;  // render.occlusion: HiZ pyramid (low 16 bits), occlusion candidates (high 16 bits)
  uint drawCount;  // kCullDrawCountMask; kCullOcclusion, kCullReversedZ, kCullHoldBackOdd
  // render.lod_error in scene pixels (times render.ssaa); 0: full detail, level 0 only (also where
  // the render path's plan says no LOD).
  // The pixels per unit length come from the frame's projection (FrameConstants), which a camera
  // path may change.
  float lodThreshold;
};
FGB_CHECK_PUSH(ClusterCullPush, 36)
// drawCount's top bits (render.occlusion):
const uint kCullOcclusion = 0x80000000u;  // test against last frame's HiZ pyramid (where FrameConstants has kFrameHizValid)
const uint kCullReversedZ = 0x40000000u;
const uint kCullHoldBackOdd = 0x20000000u;  // debug.occlusion_hold_back: odd clusters are candidates too
const uint kCullDrawCountMask = 0x1fffffffu;

// "Cluster Cull (late)" (cluster_cull_late.comp).
struct LateCullPush {
  uint frame;
  uint instances;
  uint draws;
  uint clusters;
  uint hiz;         // this frame's pyramid so far (read)
  uint candidates;  // ClusterDraw indices held back by phase 1 (read)
  uint earlyArgs;   // phase 1's counters (read): candidates, phase-1 visible clusters
  uint counters;    // the late counters (read-write)
  uint visible;     // the visible-cluster list (appended to)
  uint reversedZ;
};
FGB_CHECK_PUSH(LateCullPush, 40)

// "HiZ Build" (hiz_build.comp).
struct HizPush {
  uint words;   // level 1: the visibility buffer (storage buffer, or R64 image: render.vis_backing);
                // variant "depth": the depth texture's sampled index
  uint hiz;     // the pyramid (read-write)
  uint width;   // the viewport
  uint height;
  uint sourceLevel;   // the level read (0: the depths; a multiple of FGB_HIZ_PASS_LEVELS): the
                      // dispatch writes the FGB_HIZ_PASS_LEVELS levels after it (those that exist)
  uint fetchSampler;  // variant "depth": a sampler for the fetch
  uint reversedZ;     // variant "depth": the depth keys' convention
};
FGB_CHECK_PUSH(HizPush, 28)

// The raster's indirect arguments (vis_args.comp).
struct ArgsPush {
  uint counters;       // read
  uint args;           // written: the counters with the arguments filled in
  uint smallPerGroup;  // small triangles per raster workgroup
  uint tileJobCapacity;
};
FGB_CHECK_PUSH(ArgsPush, 16)

// "Visibility Clear" of the R64 image backing (vis_clear.comp).
struct ClearPush {
  uint words;  // storage-texture index of the visibility image
  uint width;
  uint height;
};
FGB_CHECK_PUSH(ClearPush, 12)

// "Triangle Filter", "Visibility Raster" and "Material Shade" (visbuffer_triangle.glsl).
struct VisPush {
  uint frame;
  uint instances;
  uint materials;
  uint draws;
  uint clusters;
  uint indices;         // cluster triangles (packed 8-bit cluster-local indices, ClusterData)
  uint vertices;        // the scene's vertex buffer (streams at the float offsets below)
  uint positions;       // cluster vertices (uvec4: position as float bits, w: its vertex in `vertices`)
  uint normals;         // float offsets of the vertex streams
  uint tangents;
  uint uvs;
  uint counters;        // VisCounters the culling nodes add to ("Material Shade": the host's copy of both phases')
  uint args;            // VisCounters snapshot with the indirect arguments of this node ("Material
                        // Shade": phase 1's in the low 16 bits, phase 2's in the high, kVisNoPhase for none)
  uint visible;         // visible-cluster list
  uint smallList;       // ids of small triangles
  uint largeList;       // kLargeTriangleBytes per large triangle, set up by "Triangle Filter" (packLargeTriangle)
  uint largeCapacity;
  uint words;           // the visibility buffer (uint64 per pixel)
  uint depthOut;        // float per pixel, the later colour passes' depth test (opaque_depth.glsl)
  uint hdr;             // storage image index of the HDR target
  uint materialSampler;
  uint lights;
  uint clusterCounts;   // FGB_NONE: no clustered lighting
  uint clusterIndices;
  uint flags;           // kFlagReversedZ, kFlagLargeTiles, kFlagSerialSubgroups
  uint tileJobs;        // kTileJobBytes per tile job: large-list slot, job index within the triangle
  uint tileJobCapacity;
  uint depthCompare;    // the compute transparent passes: the opaque depth test's OpaqueDepthTest::compareOp
  vec4 background;      // (at byte 112) HDR clear of pixels no triangle covers (pre-exposed, alpha 0)
};
FGB_CHECK_PUSH(VisPush, 128)
const uint kVisNoPhase = 0xffffu;  // VisPush::args of "Material Shade" without render.occlusion
const uint kFlagReversedZ = 1u;
const uint kFlagLargeTiles = 2u;        // raster the large-triangle tiles (else the small triangles)
const uint kFlagSerialSubgroups = 4u;   // a CPU device: a workgroup's subgroups run one after another
const uint kFlagInjectBias = 8u;        // debug.inject_bias=Material Shade: + kInjectedBias (debug.h)
const uint kLargeTriangleBytes = 64u;   // 4 uvec4 (packLargeTriangle in visbuffer_triangle.glsl)
const uint kTileJobBytes = 8u;          // uvec2: large-list slot, job index within the triangle

FGB_GPU_END

#endif
