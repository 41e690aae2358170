// The one place where a frame graph's GPU timestamps become the harness's frame timings: every
// Workload that renders through an rhi::ExecutableGraph (the scene workload, the proof scene)
// executes its frames through a GraphFrameTimer, so `run`, `bless`, `sweep` and `stress` read
// timings made the same way whichever workload they open.
#pragma once

#include <deque>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/renderer/workload.hpp>
#include <fgb/rhi/device.hpp>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fgb::render {

// Executes one graph frame after frame and hands back each frame's timings once the GPU has them.
// Invariant: every executed frame yields exactly one FrameTiming, in execution order, either from
// a later execute() or from finish().
class GraphFrameTimer {
 public:
  // Executes `graph` once and returns the oldest frame whose timings are complete, or a timing
  // with no passes when none is ready yet (timestamps of frame N normally arrive during N+1).
  // `updateMs`: host time spent writing this frame's per-frame values, counted as its CPU time.
  // `pathTimeS`: the frame's camera-path time (FrameTiming::pathTimeS).
  FrameTiming execute(rhi::Device& device, rhi::ExecutableGraph& graph, double updateMs = 0.0,
                      double pathTimeS = -1.0) {
    const rhi::RunTicket ticket = device.execute(graph);
    lastTicket_ = ticket;
    hostTimes_[ticket.execution] = {graph.lastHostTimes(), updateMs, pathTimeS};
    collect(graph);
    if (ready_.empty()) return {};
    FrameTiming oldest = std::move(ready_.front());
    ready_.pop_front();
    return oldest;
  }

  // Executes `graph` once with each node alone on an idle device (rhi::RunMode::Isolated) and
  // returns that frame's timings, its passes' isolated costs. Frames not handed back yet are
  // dropped: calibrate after finish(). `updateMs`, `pathTimeS`: as for execute().
  FrameTiming executeIsolated(rhi::Device& device, rhi::ExecutableGraph& graph, double updateMs = 0.0,
                              double pathTimeS = -1.0) {
    const rhi::RunTicket ticket = device.execute(graph, rhi::RunMode::Isolated);
    lastTicket_ = ticket;
    hostTimes_[ticket.execution] = {graph.lastHostTimes(), updateMs, pathTimeS};
    std::vector<FrameTiming> done = finish(device, graph);
    return done.empty() ? FrameTiming{} : std::move(done.back());
  }

  [[nodiscard]] const rhi::RunTicket& lastTicket() const { return lastTicket_; }

  // Waits for the device and returns the timings of every frame not handed back yet.
  std::vector<FrameTiming> finish(rhi::Device& device, rhi::ExecutableGraph& graph) {
    device.waitIdle();
    collect(graph);
    std::vector<FrameTiming> rest(std::make_move_iterator(ready_.begin()), std::make_move_iterator(ready_.end()));
    ready_.clear();
    return rest;
  }

 private:
  void collect(rhi::ExecutableGraph& graph) {
    for (const auto& timings : graph.takeTimings()) ready_.push_back(toFrameTiming(graph, timings));
  }

  // Every declared node, in declaration order. Culled nodes and nodes the backend gave no
  // timestamp report 0 ms and no start (-1: the pass's queue family has no timestamps).
  FrameTiming toFrameTiming(const rhi::ExecutableGraph& graph, const rhi::GraphTimings& timings) {
    const auto& nodes = graph.declaration().nodes();
    const auto& compiled = graph.compiled().nodes;
    FrameTiming frame;
    frame.passes.reserve(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const bool culled = compiled[i].culled;
      const bool timed = !culled && i < timings.nodeMs.size() && i < timings.nodeStartMs.size();
      frame.passes.push_back({std::string(nodes[i].name), std::string(graph::toString(nodes[i].queue)), culled,
                              timed ? timings.nodeMs[i] : 0.0, timed ? timings.nodeStartMs[i] : -1.0});
    }
    frame.gpuFrameMs = timings.gpuMs;
    frame.gpuFrameStartMs = timings.startMs;
    if (const auto host = hostTimes_.find(timings.execution); host != hostTimes_.end()) {
      frame.cpuFrameMs = host->second.updateMs + host->second.graph.recordMs;
      frame.submitMs = host->second.graph.submitMs;
      frame.nodesRecorded = host->second.graph.nodesRecorded;
      frame.nodesReused = host->second.graph.nodesReused;
      frame.pathTimeS = host->second.pathTimeS;
      hostTimes_.erase(host);
    }
    return frame;
  }

  rhi::RunTicket lastTicket_;
  std::deque<FrameTiming> ready_;
  // Host times (per-frame values written, recording, submit, nodes recorded/reused) and the
  // camera-path time by execution, until its timings arrive.
  struct HostFrame {
    rhi::ExecutableGraph::HostTimes graph;
    double updateMs = 0.0;
    double pathTimeS = -1.0;
  };
  std::unordered_map<uint64_t, HostFrame> hostTimes_;
};

}  // namespace fgb::render
