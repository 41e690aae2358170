// Compiles a declared FrameGraph into a CompiledGraph, in stages (compiler.cpp runs them in order):
//   1. resources: dependent fields resolved to values;
//   2. culling by flood fill back from imported resources and side-effect nodes, a reason per node;
//   3. dependency edges among alive nodes from versions (RAW, WAR, WAW, reader chains), their
//      longest-path levels, and cycle detection over every declared node (names the cycle);
//   4. a topological order, stable-sorted by level;
//   5. SSIS pruning of cross-queue edges (thesis Algorithm 3), giving G*;
//   6. steps and submits with timeline values;
//   7. one walk over the uses in order: lifetimes, transient memory aliasing by placement (a range is
//      reused only once every queue that touched it has been waited for), and the barrier plan
//      (transitions, ownership release/acquire, first use from UNDEFINED).
// Every stage is linear in nodes + resources + uses + edges, but for placement's search of free
// ranges and SSIS's greedy cover (both bounded by small factors: free ranges per heap, queues).
#pragma once

#include <array>
#include <fgb/graph/compiled_graph.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <functional>

namespace fgb::graph {

// Wall time of each compiler stage, summed over the compiles it was handed to (see
// CompileOptions::profile). Indexed by CompileStage.
enum class CompileStage : uint8_t { Resources, Cull, Dependencies, Sort, Ssis, Submits, Barriers, Count };
const char* toString(CompileStage stage);

struct CompileProfile {
  std::array<double, static_cast<size_t>(CompileStage::Count)> microseconds{};
  uint64_t compiles = 0;
};

struct CompileOptions {
  uint32_t queueCount = 1;
  // Queue index for each QueueClass (Graphics, Compute, Transfer); each must be < queueCount.
  std::array<uint32_t, kQueueClassCount> queueOfClass{0, 0, 0};
  // Queue family of each queue index; ownership transfers happen only between different families.
  std::array<uint32_t, kQueueClassCount> familyOfQueue{0, 1, 2};
  // Buffers are created shareable by every queue family (Vulkan's CONCURRENT sharing mode): they
  // change queues with no ownership transfer (semaphores still order them); only textures transfer.
  bool buffersShareFamilies = false;
  bool cull = true;
  bool alias = true;
  // Size/alignment/memory types of a transient resource (backend: vkGet*MemoryRequirements).
  std::function<MemoryRequirements(const ResourceDecl&, const ResolvedResource&)> requirements;
  // When set, each stage's wall time is added to it (benchmarks; off by default: no clock reads).
  CompileProfile* profile = nullptr;
};

// Simple requirements model for tests and when no device is present: tightly packed texels
// (times samples, plus the mip chain), 256-byte alignment, any memory type.
MemoryRequirements estimateRequirements(const ResourceDecl& decl, const ResolvedResource& resolved);

// Throws GraphError on bad declarations (cycles, dependent fields naming unknown resources, ...).
CompiledGraph compile(const FrameGraph& graph, const CompileOptions& options = {});

}  // namespace fgb::graph
