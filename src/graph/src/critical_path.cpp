#include <algorithm>
#include <fgb/graph/critical_path.hpp>
#include <stdexcept>

namespace fgb::graph {
namespace {

// Nodes in an order where every predecessor comes first (Kahn's algorithm).
std::vector<uint32_t> topologicalOrder(const std::vector<std::vector<uint32_t>>& predecessors) {
  const size_t n = predecessors.size();
  std::vector<std::vector<uint32_t>> successors(n);
  std::vector<uint32_t> waiting(n, 0);
  for (uint32_t node = 0; node < n; ++node) {
    for (const uint32_t before : predecessors[node]) {
      successors.at(before).push_back(node);
      ++waiting[node];
    }
  }
  std::vector<uint32_t> order;
  for (uint32_t node = 0; node < n; ++node) {
    if (waiting[node] == 0) order.push_back(node);
  }
  for (size_t i = 0; i < order.size(); ++i) {
    for (const uint32_t next : successors[order[i]]) {
      if (--waiting[next] == 0) order.push_back(next);
    }
  }
  if (order.size() != n) throw std::invalid_argument("criticalPath: the schedule has a cycle");
  return order;
}

// Longest path ending at each node (its own cost included), in `order`.
std::vector<double> longestEndingAt(const std::vector<std::vector<uint32_t>>& predecessors,
                                    const std::vector<uint32_t>& order, std::span<const double> costMs) {
  std::vector<double> end(predecessors.size(), 0.0);
  for (const uint32_t node : order) {
    double start = 0.0;
    for (const uint32_t before : predecessors[node]) start = std::max(start, end[before]);
    end[node] = start + costMs[node];
  }
  return end;
}

double maxOf(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

}  // namespace

std::vector<std::vector<uint32_t>> schedulePredecessors(const CompiledGraph& compiled) {
  std::vector<std::vector<uint32_t>> predecessors(compiled.nodes.size());
  for (const Edge& edge : compiled.edges) predecessors[edge.to].push_back(edge.from);
  // Per queue, the last step of each submit in signal order: what a semaphore wait waits for.
  std::vector<std::vector<uint32_t>> lastNodeOfSubmit(compiled.queueCount);
  for (const Submit& submit : compiled.submits) {
    if (submit.stepCount == 0) continue;
    auto& perQueue = lastNodeOfSubmit[submit.queue];
    perQueue.resize(std::max<size_t>(perQueue.size(), submit.signalValue));
    perQueue[submit.signalValue - 1] = compiled.steps[submit.firstStep + submit.stepCount - 1].node;
  }
  for (const Submit& submit : compiled.submits) {
    for (uint32_t s = submit.firstStep; s < submit.firstStep + submit.stepCount; ++s) {
      const uint32_t node = compiled.steps[s].node;
      if (s > submit.firstStep) {
        predecessors[node].push_back(compiled.steps[s - 1].node);
        continue;
      }
      for (const SemaphoreWait& wait : submit.waits) {
        const auto& signals = lastNodeOfSubmit[wait.queue];
        if (wait.value >= 1 && wait.value <= signals.size()) predecessors[node].push_back(signals[wait.value - 1]);
      }
    }
  }
  // The first step of a submit follows the last step of the queue's previous submit.
  for (uint32_t q = 0; q < compiled.queueCount; ++q) {
    uint32_t previous = kInvalidIndex;
    for (const Submit& submit : compiled.submits) {
      if (submit.queue != q || submit.stepCount == 0) continue;
      const uint32_t first = compiled.steps[submit.firstStep].node;
      if (previous != kInvalidIndex) predecessors[first].push_back(previous);
      previous = compiled.steps[submit.firstStep + submit.stepCount - 1].node;
    }
  }
  for (auto& list : predecessors) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return predecessors;
}

CriticalPath criticalPath(const std::vector<std::vector<uint32_t>>& predecessors, std::span<const double> costMs) {
  if (costMs.size() != predecessors.size()) throw std::invalid_argument("criticalPath: one cost per node");
  const std::vector<uint32_t> order = topologicalOrder(predecessors);
  const std::vector<double> end = longestEndingAt(predecessors, order, costMs);
  CriticalPath path;
  path.lengthMs = maxOf(end);
  path.shareOfPath.assign(costMs.size(), 0.0);
  path.onPath.assign(costMs.size(), false);
  if (path.lengthMs <= 0.0) return path;
  // Graphs have 20-500 passes: recomputing the path once per pass is clear and cheap enough.
  std::vector<double> without(costMs.begin(), costMs.end());
  for (uint32_t node = 0; node < costMs.size(); ++node) {
    if (costMs[node] <= 0.0) continue;
    without[node] = 0.0;
    const double shorter = path.lengthMs - maxOf(longestEndingAt(predecessors, order, without));
    without[node] = costMs[node];
    path.shareOfPath[node] = shorter / path.lengthMs;
  }
  // On a longest chain: walk back from the end through predecessors that end where this starts.
  std::vector<uint32_t> stack;
  for (uint32_t node = 0; node < end.size(); ++node) {
    if (end[node] >= path.lengthMs * (1.0 - 1e-12)) stack.push_back(node);
  }
  while (!stack.empty()) {
    const uint32_t node = stack.back();
    stack.pop_back();
    if (path.onPath[node]) continue;
    path.onPath[node] = true;
    const double start = end[node] - costMs[node];
    for (const uint32_t before : predecessors[node]) {
      if (end[before] >= start - 1e-12 * path.lengthMs && !path.onPath[before]) stack.push_back(before);
    }
  }
  return path;
}

}  // namespace fgb::graph
