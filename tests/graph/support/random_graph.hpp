// Random frame-graph declarations for property tests. Deterministic for a given seed. Most reads
// take the latest version; a few take an older one, which adds WAR edges and can close a cycle
// (the property tests then expect compile() to report it).
#pragma once

#include "graph_model.hpp"

#include <fgb/graph/compiler.hpp>

#include <cstdint>
#include <memory>

namespace fgb::graph::test {

struct RandomGraphParams {
  uint32_t nodes = 20;
  uint32_t queueCount = 3;
  double oldVersionReadChance = 0.03;  // reads of a non-latest version (may close cycles)
  double sideEffectChance = 0.08;
};

struct RandomGraph {
  std::unique_ptr<FrameGraph> graph;  // FrameGraph owns no self-pointers, but keep it pinned anyway
  GraphModel model;                   // recorded by the generator, independent of the library
};

RandomGraph makeRandomGraph(uint32_t seed, const RandomGraphParams& params);

// Options for `queueCount` queues (queueOfClassFor) with a requirements model that mixes
// alignments and memory types so aliasing must respect compatibility.
CompileOptions randomCompileOptions(uint32_t queueCount);

}  // namespace fgb::graph::test
