// Declare + compile of the pure frame graph (everything the compiler does: edges, culling, levels,
// SSIS, submits, lifetimes, aliasing, barriers) for 100 / 1,000 / 10,000 nodes in two shapes:
//   chain   — node i reads node i-1's output and writes a new transient; the last is a side effect;
//   layered — layers of width 8; each node reads 2 distinct outputs of the previous layer chosen
//             with std::mt19937(42)() % 8 (drawn once, before timing) and writes one new
//             transient; the last layer is a side effect.
// Q = 1 (every class on queue 0) and Q = 3 (graphics/compute/transfer on queues 0/1/2). Node types
// follow a fixed mix (graphics, compute, graphics, transfer, ...) in both cases.
// Target (issue): the 10,000-node layered DAG declares and compiles in <= 1.5 ms median on one core.
#include <fgb/graph/compiler.hpp>

#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace fgb::graph;

constexpr uint32_t kLayerWidth = 8;

NodeType typeOf(uint32_t node) {
  static constexpr NodeType kMix[] = {NodeType::Graphics, NodeType::Compute, NodeType::Graphics,
                                      NodeType::Transfer};
  return kMix[node % 4];
}

Access writeAccess(NodeType type) {
  switch (type) {
    case NodeType::Graphics: return Access::ColorAttachmentWrite;
    case NodeType::Compute: return Access::StorageWrite;
    case NodeType::Transfer: return Access::TransferDst;
  }
  return Access::StorageWrite;
}

Access readAccess(NodeType type) { return type == NodeType::Transfer ? Access::TransferSrc : Access::Sampled; }

TextureDesc targetDesc() {
  TextureDesc desc;
  desc.format = Format::R16G16B16A16Sfloat;
  desc.extent = {256, 256, 1};
  return desc;
}

// Everything the timed loop declares from, made once outside it: building strings and drawing
// random numbers are not the graph's cost (the seed is fixed, so every iteration declares the
// same graph either way).
struct ShapeInputs {
  explicit ShapeInputs(uint32_t count) {
    for (uint32_t i = 0; i < count; ++i) {
      nodes.push_back("node" + std::to_string(i));
      resources.push_back("tex" + std::to_string(i));
    }
    std::mt19937 rng(42);
    for (uint32_t layer = 1; layer < count / kLayerWidth; ++layer) {
      for (uint32_t slot = 0; slot < kLayerWidth; ++slot) {
        const uint32_t first = rng() % kLayerWidth;
        uint32_t second = rng() % kLayerWidth;
        while (second == first) second = rng() % kLayerWidth;  // two distinct outputs
        layeredInputs.push_back({first, second});
      }
    }
  }
  std::vector<std::string> nodes;
  std::vector<std::string> resources;
  // Layered shape: for each node past the first layer, the two slots of the previous layer it reads.
  std::vector<std::array<uint32_t, 2>> layeredInputs;
};

// Declares node `i` reading `reads` and writing a fresh transient; returns what it wrote.
TextureHandle declareNode(FrameGraph& graph, const ShapeInputs& inputs, uint32_t i, const TextureHandle* reads,
                          uint32_t readCount, bool sideEffect) {
  const TextureHandle target = graph.createTexture(inputs.resources[i], targetDesc());
  const NodeType type = typeOf(i);
  NodeBuilder builder = graph.addNode(inputs.nodes[i], type);
  for (uint32_t k = 0; k < readCount; ++k) builder.read(reads[k], readAccess(type));
  const TextureHandle written = builder.write(target, writeAccess(type));
  if (sideEffect) builder.sideEffect();
  return written;
}

void declareChain(FrameGraph& graph, const ShapeInputs& inputs, uint32_t count) {
  TextureHandle previous{};
  for (uint32_t i = 0; i < count; ++i) {
    previous = declareNode(graph, inputs, i, &previous, i == 0 ? 0 : 1, i + 1 == count);
  }
}

void declareLayered(FrameGraph& graph, const ShapeInputs& inputs, uint32_t count) {
  std::array<TextureHandle, kLayerWidth> previousLayer{};
  std::array<TextureHandle, kLayerWidth> currentLayer{};
  const uint32_t layers = count / kLayerWidth;
  const std::array<uint32_t, 2>* chosen = inputs.layeredInputs.data();
  for (uint32_t layer = 0; layer < layers; ++layer) {
    const bool last = layer + 1 == layers;
    for (uint32_t slot = 0; slot < kLayerWidth; ++slot) {
      const uint32_t i = layer * kLayerWidth + slot;
      TextureHandle reads[2];
      uint32_t readCount = 0;
      if (layer > 0) {
        reads[0] = previousLayer[(*chosen)[0]];
        reads[1] = previousLayer[(*chosen)[1]];
        readCount = 2;
        ++chosen;
      }
      currentLayer[slot] = declareNode(graph, inputs, i, reads, readCount, last);
    }
    std::swap(previousLayer, currentLayer);
  }
}

CompileOptions optionsFor(uint32_t queues) {
  CompileOptions options;
  options.queueCount = queues;
  options.queueOfClass = queues == 1 ? std::array<uint32_t, 3>{0, 0, 0} : std::array<uint32_t, 3>{0, 1, 2};
  return options;
}

template <void (*Declare)(FrameGraph&, const ShapeInputs&, uint32_t)>
void declareAndCompile(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  const CompileOptions options = optionsFor(static_cast<uint32_t>(state.range(1)));
  const ShapeInputs inputs(count);
  size_t barriers = 0;
  for (auto _ : state) {
    FrameGraph graph;
    graph.reserve(count, count);
    Declare(graph, inputs, count);
    const CompiledGraph compiled = compile(graph, options);
    barriers = compiled.barriers.size();
    benchmark::DoNotOptimize(compiled.steps.data());
  }
  state.counters["nodes"] = count;
  state.counters["barriers"] = static_cast<double>(barriers);
  state.counters["ns_per_node"] =
      benchmark::Counter(static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate |
                                                         benchmark::Counter::kInvert);
}

void shapes(benchmark::internal::Benchmark* bench) {
  bench->ArgNames({"nodes", "Q"});
  for (int64_t queues : {1, 3}) {
    for (int64_t nodes : {100, 1000, 10000}) bench->Args({nodes, queues});
  }
  bench->Unit(benchmark::kMicrosecond);
}

// The same, with each compiler stage's mean time as a counter (us), and the declaration (with the
// graphs' destruction) as "declare": where the time goes. Apart from the rows above, which read no
// clock inside compile().
template <void (*Declare)(FrameGraph&, const ShapeInputs&, uint32_t)>
void declareAndCompileByStage(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  CompileOptions options = optionsFor(static_cast<uint32_t>(state.range(1)));
  CompileProfile profile;
  options.profile = &profile;
  const ShapeInputs inputs(count);
  for (auto _ : state) {
    FrameGraph graph;
    graph.reserve(count, count);
    Declare(graph, inputs, count);
    const CompiledGraph compiled = compile(graph, options);
    benchmark::DoNotOptimize(compiled.steps.data());
  }
  double compileTotal = 0;
  for (size_t s = 0; s < profile.microseconds.size(); ++s) {
    const double mean = profile.microseconds[s] / static_cast<double>(profile.compiles);
    state.counters[toString(static_cast<CompileStage>(s))] = mean;
    compileTotal += mean;
  }
  state.counters["compile"] = compileTotal;
}

void largestShapes(benchmark::internal::Benchmark* bench) {
  bench->ArgNames({"nodes", "Q"});
  for (int64_t queues : {1, 3}) bench->Args({10000, queues});
  bench->Unit(benchmark::kMicrosecond);
}

BENCHMARK(declareAndCompile<declareChain>)->Name("DeclareCompile/chain")->Apply(shapes);
BENCHMARK(declareAndCompile<declareLayered>)->Name("DeclareCompile/layered")->Apply(shapes);
BENCHMARK(declareAndCompileByStage<declareChain>)->Name("CompileStages/chain")->Apply(largestShapes);
BENCHMARK(declareAndCompileByStage<declareLayered>)->Name("CompileStages/layered")->Apply(largestShapes);

}  // namespace

BENCHMARK_MAIN();
