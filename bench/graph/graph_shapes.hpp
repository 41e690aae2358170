// The graph shapes graph_bench and graph_scaling_test declare and compile, for N nodes:
//   chain   — node i reads node i-1's output and writes a new transient; the last is a side effect;
//   layered — layers of width 8; each node reads 2 distinct outputs of the previous layer chosen
//             with std::mt19937(42)() % 8 (drawn once, before timing) and writes one new
//             transient; the last layer is a side effect.
// Node types follow a fixed mix (graphics, compute, graphics, transfer, ...). optionsFor(1) puts
// every class on queue 0, optionsFor(3) graphics/compute/transfer on queues 0/1/2.
#pragma once

#include <array>
#include <cstdint>
#include <fgb/graph/compiler.hpp>
#include <string>
#include <vector>

namespace fgb::graph::bench {

// Everything a declaration draws on, made once outside any timed loop: building strings and
// drawing random numbers are not the graph's cost (the seed is fixed, so every declaration of a
// shape is the same graph).
struct ShapeInputs {
  explicit ShapeInputs(uint32_t count);
  uint32_t count;
  std::vector<std::string> nodes;
  std::vector<std::string> resources;
  // Layered shape: for each node past the first layer, the two slots of the previous layer it reads.
  std::vector<std::array<uint32_t, 2>> layeredInputs;
};

using DeclareShape = void (*)(FrameGraph& graph, const ShapeInputs& inputs);
void declareChain(FrameGraph& graph, const ShapeInputs& inputs);
void declareLayered(FrameGraph& graph, const ShapeInputs& inputs);

CompileOptions optionsFor(uint32_t queues);

// Keeps freed memory in the process (glibc only): a benchmark that declares and compiles in a
// loop then measures the graph, not the kernel faulting in again the pages that glibc handed back
// after the previous iteration (which it does only once a graph's arrays pass its trim threshold,
// so between 1,000 and 10,000 nodes: a step in cost that is not the compiler's).
void keepFreedMemory();

}  // namespace fgb::graph::bench
