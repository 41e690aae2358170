// Execute with empty jobs, 100 / 1,000 / 10,000 nodes, two shapes (as in bench/graph):
//   chain   — node i reads node i-1's output and writes a new transient; the last is a side effect;
//   layered — layers of width 8; each node reads 2 distinct outputs of the previous layer chosen
//             with std::mt19937(42)() % 8 and writes one new transient; the last layer is a side
//             effect.
// Q = 1 and Q = 3 logical queues (on lavapipe all map to its one queue, and so are one queue; the
// "separate:1" rows keep them apart there, to show the cost of submits and semaphores). Node types cycle
// graphics, compute, graphics, transfer; resources are 256-byte transient buffers.
//   Execute/...        : record + submit of one execution (CPU), the GPU idle at the start.
//   ExecuteAndWait/... : one execution end to end, including the device running it.
//   ExecuteRecording/... : as Execute, but every job records one command (a 4-byte vkCmdFillBuffer
//             of its output; all accesses are transfer accesses), so every node pays its barriers,
//             timestamps and the command: the executor's cost per node that does work.
//   ExecuteRecording/layered_reuse, .../layered_record_every_frame : the same graph, every node
//             declaring a constant recording key (NodeBuilder::recordingFixed): with reuse its kept
//             command buffers are submitted again; with debug.record_every_frame every job runs.
//             layered_reuse keeps one buffer per submit (a block, the default), and
//             layered_reuse_node_buffers one per node (debug.node_buffers).
//             Counters record_us and submit_us: the executor's host times per execution.
// Timestamps on, debug labels off (labels cost one call pair per node; see the "labels" variant).
// Target (issue): execute with empty jobs in <= 0.5 ms for 10,000 nodes on one core. Empty jobs
// record nothing, so the executor records no barrier, timestamp or label for them (it defers all
// of them to a node's first command); what remains is its own walk over the steps.
// Device: FGBENCH_BENCH_DEVICE (default auto).
#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/device.hpp>
#include <fgb/rhi/job_context.hpp>
#include <fgb/vulkan/backend.hpp>

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace fgb;
using namespace fgb::graph;

constexpr uint32_t kLayerWidth = 8;

// Made on first use, destroyed by main() before it returns: as static destructors they would run
// after the driver's own exit handlers (the NVIDIA driver then crashed the process at exit).
std::unique_ptr<rhi::Device> benchDevices[2];

rhi::Device& benchDevice(bool labels) {
  auto& device = benchDevices[labels ? 1 : 0];
  if (!device) {
    const char* selector = std::getenv("FGBENCH_BENCH_DEVICE");
    device = vulkan::createDevice({.selector = selector ? selector : "auto", .validation = false, .debugLabels = labels});
  }
  return *device;
}

NodeType typeOf(uint32_t node) {
  static constexpr NodeType kMix[] = {NodeType::Graphics, NodeType::Compute, NodeType::Graphics, NodeType::Transfer};
  return kMix[node % 4];
}

bool gRecordingJobs = false;  // set while building the graphs of the ExecuteRecording variant
bool gKeyedJobs = false;      // ... and their nodes declare a constant recording key

BufferHandle declareNode(FrameGraph& graph, uint32_t i, const BufferHandle* inputs, uint32_t inputCount, bool sideEffect) {
  const NodeType type = typeOf(i);
  BufferHandle target = graph.createBuffer("buf" + std::to_string(i), {256});
  NodeBuilder node = graph.addNode("node" + std::to_string(i), type);
  const bool transfer = type == NodeType::Transfer || gRecordingJobs;
  for (uint32_t k = 0; k < inputCount; ++k) node.read(inputs[k], transfer ? Access::TransferSrc : Access::StorageRead);
  target = node.write(target, transfer ? Access::TransferDst : Access::StorageWrite);
  if (sideEffect) node.sideEffect();
  if (gRecordingJobs) {
    node.setJob([target, i](JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().fillBuffer(ctx.buffer(target), 0, 4, i);
    });
    if (gKeyedJobs) node.recordingFixed();
  } else {
    node.setJob([](JobContext&) {});  // empty job: the executor's own cost is what is measured
  }
  return target;
}

FrameGraph chain(uint32_t count) {
  FrameGraph graph;
  BufferHandle previous{};
  for (uint32_t i = 0; i < count; ++i) previous = declareNode(graph, i, &previous, i == 0 ? 0 : 1, i + 1 == count);
  return graph;
}

FrameGraph layered(uint32_t count) {
  FrameGraph graph;
  std::mt19937 rng(42);
  std::vector<BufferHandle> previousLayer(kLayerWidth);
  std::vector<BufferHandle> currentLayer(kLayerWidth);
  const uint32_t layers = count / kLayerWidth;
  for (uint32_t layer = 0; layer < layers; ++layer) {
    for (uint32_t slot = 0; slot < kLayerWidth; ++slot) {
      BufferHandle inputs[2];
      uint32_t inputCount = 0;
      if (layer > 0) {
        const uint32_t first = rng() % kLayerWidth;
        uint32_t second = rng() % kLayerWidth;
        while (second == first) second = rng() % kLayerWidth;
        inputs[0] = previousLayer[first];
        inputs[1] = previousLayer[second];
        inputCount = 2;
      }
      currentLayer[slot] = declareNode(graph, layer * kLayerWidth + slot, inputs, inputCount, layer + 1 == layers);
    }
    std::swap(previousLayer, currentLayer);
  }
  return graph;
}

void addCounters(benchmark::State& state, const rhi::ExecutableGraph& graph, uint32_t count) {
  state.counters["nodes"] = count;
  state.counters["barriers"] = static_cast<double>(graph.compiled().barriers.size());
  state.counters["submits"] = static_cast<double>(graph.compiled().submits.size());
  state.counters["ns_per_node"] = benchmark::Counter(
      static_cast<double>(count), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

enum class Keys { None, Reuse, ReuseNodeBuffers, RecordEveryFrame };

template <FrameGraph (*Shape)(uint32_t), bool Labels = false, bool Recording = false, Keys keys = Keys::None>
void executeOnly(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  const auto queues = static_cast<uint32_t>(state.range(1));
  const bool separate = state.range(2) != 0;
  rhi::Device& device = benchDevice(Labels);
  gRecordingJobs = Recording;
  gKeyedJobs = keys != Keys::None;
  auto graph = device.compile(Shape(count), {.name = "bench",
                                             .queues = queues,
                                             .separateQueues = separate,
                                             .timestamps = true,
                                             .recordEveryFrame = keys == Keys::RecordEveryFrame,
                                             .nodeBuffers = keys == Keys::ReuseNodeBuffers});
  gRecordingJobs = gKeyedJobs = false;
  // Warm: first-use allocations out of the way, and every frame-in-flight slot recorded once.
  for (int i = 0; i < 3; ++i) device.wait(device.execute(*graph));
  double recordMs = 0.0;
  double submitMs = 0.0;
  for (auto _ : state) {
    const rhi::RunTicket ticket = device.execute(*graph);
    state.PauseTiming();
    recordMs += graph->lastHostTimes().recordMs;
    submitMs += graph->lastHostTimes().submitMs;
    device.wait(ticket);
    graph->takeTimings();
    state.ResumeTiming();
  }
  addCounters(state, *graph, count);
  const auto perExecution = [&](double ms) {
    return benchmark::Counter(ms * 1000.0, benchmark::Counter::kAvgIterations);
  };
  state.counters["record_us"] = perExecution(recordMs);
  state.counters["submit_us"] = perExecution(submitMs);
}

template <FrameGraph (*Shape)(uint32_t)>
void executeAndWait(benchmark::State& state) {
  const auto count = static_cast<uint32_t>(state.range(0));
  const auto queues = static_cast<uint32_t>(state.range(1));
  const bool separate = state.range(2) != 0;
  rhi::Device& device = benchDevice(false);
  auto graph = device.compile(Shape(count), {.name = "bench", .queues = queues, .separateQueues = separate, .timestamps = true});
  device.wait(device.execute(*graph));
  for (auto _ : state) {
    device.wait(device.execute(*graph));
    graph->takeTimings();
  }
  addCounters(state, *graph, count);
}

void shapes(benchmark::internal::Benchmark* bench) {
  bench->ArgNames({"nodes", "Q", "separate"});
  for (int64_t queues : {1, 3}) {
    for (int64_t nodes : {100, 1000, 10000}) bench->Args({nodes, queues, 0});
  }
  bench->Args({10000, 3, 1});
  bench->Unit(benchmark::kMicrosecond);
}

BENCHMARK(executeOnly<chain>)->Name("Execute/chain")->Apply(shapes);
BENCHMARK(executeOnly<layered>)->Name("Execute/layered")->Apply(shapes);
BENCHMARK(executeAndWait<chain>)->Name("ExecuteAndWait/chain")->Apply(shapes);
BENCHMARK(executeAndWait<layered>)->Name("ExecuteAndWait/layered")->Apply(shapes);
BENCHMARK(executeOnly<chain, false, true>)->Name("ExecuteRecording/chain")->Apply(shapes);
BENCHMARK(executeOnly<layered, false, true>)->Name("ExecuteRecording/layered")->Apply(shapes);
// Kept command buffers against recording every frame: the same keyed graph, 500 and 1,000 nodes.
void reuseShapes(benchmark::internal::Benchmark* bench) {
  bench->ArgNames({"nodes", "Q", "separate"});
  for (int64_t queues : {1, 3}) {
    for (int64_t nodes : {500, 1000}) bench->Args({nodes, queues, 0});
  }
  bench->Unit(benchmark::kMicrosecond);
}
BENCHMARK(executeOnly<layered, false, true, Keys::Reuse>)->Name("ExecuteRecording/layered_reuse")->Apply(reuseShapes);
BENCHMARK(executeOnly<layered, false, true, Keys::ReuseNodeBuffers>)
    ->Name("ExecuteRecording/layered_reuse_node_buffers")
    ->Apply(reuseShapes);
BENCHMARK(executeOnly<layered, false, true, Keys::RecordEveryFrame>)
    ->Name("ExecuteRecording/layered_record_every_frame")
    ->Apply(reuseShapes);
BENCHMARK(executeOnly<layered, true>)
    ->Name("Execute/layered_with_labels")
    ->ArgNames({"nodes", "Q", "separate"})
    ->Args({10000, 1, 0})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  for (auto& device : benchDevices) device.reset();
  return 0;
}
