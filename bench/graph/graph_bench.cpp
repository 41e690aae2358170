// Declare + compile of the pure frame graph (everything the compiler does: edges, culling, levels,
// SSIS, submits, lifetimes, aliasing, barriers) for 100 / 1,000 / 10,000 nodes in the two shapes of
// graph_shapes.hpp, with Q = 1 and Q = 3. No absolute target: the product compiles about 16 nodes
// once per run. graph_scaling_test guards against cost growing faster than the node count.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "graph_shapes.hpp"

namespace {

using namespace fgb::graph;
using namespace fgb::graph::bench;

template <DeclareShape Declare>
void declareAndCompile(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  const CompileOptions options = optionsFor(static_cast<uint32_t>(state.range(1)));
  const ShapeInputs inputs(count);
  size_t barriers = 0;
  for (auto _ : state) {
    FrameGraph graph;
    Declare(graph, inputs);
    const CompiledGraph compiled = compile(graph, options);
    barriers = compiled.barriers.size();
    benchmark::DoNotOptimize(compiled.steps.data());
  }
  state.counters["nodes"] = count;
  state.counters["barriers"] = static_cast<double>(barriers);
  state.counters["ns_per_node"] = benchmark::Counter(
      static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
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
template <DeclareShape Declare>
void declareAndCompileByStage(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  CompileOptions options = optionsFor(static_cast<uint32_t>(state.range(1)));
  CompileProfile profile;
  options.profile = &profile;
  const ShapeInputs inputs(count);
  for (auto _ : state) {
    FrameGraph graph;
    Declare(graph, inputs);
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

int main(int argc, char** argv) {
  keepFreedMemory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
