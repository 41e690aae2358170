#include <fmt/format.h>

#include <algorithm>
#include <fgb/harness/results/async_check.hpp>
#include <map>
#include <utility>

namespace fgb::harness {
namespace {

using Intervals = std::vector<std::pair<double, double>>;

// Sorted, disjoint intervals covering the same time as `intervals`.
Intervals unionOf(Intervals intervals) {
  std::sort(intervals.begin(), intervals.end());
  Intervals merged;
  for (const auto& [begin, end] : intervals) {
    if (end <= begin) continue;
    if (!merged.empty() && begin <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, end);
    } else {
      merged.emplace_back(begin, end);
    }
  }
  return merged;
}

double lengthOf(const Intervals& disjoint) {
  double total = 0.0;
  for (const auto& [begin, end] : disjoint) total += end - begin;
  return total;
}

}  // namespace

double queueOverlapMs(std::span<const PassInterval> passes) {
  std::map<std::string, Intervals> perQueue;
  for (const auto& pass : passes) perQueue[pass.queue].emplace_back(pass.beginMs, pass.endMs);
  // Sweep the queues' busy edges: +1 where a queue's busy interval begins, -1 where it ends.
  std::vector<std::pair<double, int>> edges;
  for (auto& [queue, intervals] : perQueue) {
    for (const auto& [begin, end] : unionOf(std::move(intervals))) {
      edges.emplace_back(begin, +1);
      edges.emplace_back(end, -1);
    }
  }
  std::sort(edges.begin(), edges.end());  // at equal times ends (-1) come first: touching is not overlap
  double overlap = 0.0;
  int busy = 0;
  double since = 0.0;
  for (const auto& [time, step] : edges) {
    if (busy >= 2) overlap += time - since;
    busy += step;
    since = time;
  }
  return overlap;
}

double idleGapsMs(std::span<const PassInterval> passes, double spanMs) {
  Intervals all;
  for (const auto& pass : passes) all.emplace_back(pass.beginMs, pass.endMs);
  return std::max(0.0, spanMs - lengthOf(unionOf(std::move(all))));
}

AsyncComparison compareAsync(uint32_t queues, std::span<const double> asyncFramesMs,
                             std::span<const double> overlapsMs, std::vector<double> singleQueueMs,
                             std::vector<double> idleGapsMs) {
  AsyncComparison c;
  c.queues = queues;
  c.singleQueue = summarize(singleQueueMs);
  c.asyncFrame = medianConfidenceInterval(asyncFramesMs);
  c.singleQueueFrame = medianConfidenceInterval(singleQueueMs);
  c.savedMs = c.singleQueueFrame.median - c.asyncFrame.median;
  c.savedLowMs = c.singleQueueFrame.lower - c.asyncFrame.upper;
  c.savedHighMs = c.singleQueueFrame.upper - c.asyncFrame.lower;
  c.overlapMs = summarize(overlapsMs).median;
  c.singleQueueMs = std::move(singleQueueMs);
  c.idleGapsMs = std::move(idleGapsMs);
  return c;
}

AsyncComparison skippedAsync(uint32_t queues, std::string why) {
  AsyncComparison c;
  c.queues = queues;
  c.skipped = std::move(why);
  return c;
}

nlohmann::json toJson(const AsyncComparison& c) {
  nlohmann::json json{{"queues", c.queues}, {"wall_ms", c.wallMs}};
  if (!c.compared()) {
    json["skipped"] = c.skipped;
    return json;
  }
  json["frames"] = c.singleQueueMs.size();
  json["single_queue_frame_ms"] = {{"median", c.singleQueueFrame.median},
                                   {"ci_low", c.singleQueueFrame.lower},
                                   {"ci_high", c.singleQueueFrame.upper},
                                   {"p5", c.singleQueue.p5},
                                   {"p95", c.singleQueue.p95}};
  json["async_frame_ms"] = {
      {"median", c.asyncFrame.median}, {"ci_low", c.asyncFrame.lower}, {"ci_high", c.asyncFrame.upper}};
  json["saved_ms"] = {{"median", c.savedMs}, {"low", c.savedLowMs}, {"high", c.savedHighMs}};
  json["queue_overlap_ms"] = c.overlapMs;
  json["single_queue_idle_gaps_ms"] = summarize(c.idleGapsMs).median;
  json["samples"] = {{"single_queue_frame_ms", c.singleQueueMs}, {"single_queue_idle_gaps_ms", c.idleGapsMs}};
  return json;
}

std::string describeAsync(const AsyncComparison& c) {
  if (!c.compared()) return "async compute: not measured (" + c.skipped + ")";
  const bool decided = c.savedLowMs > 0.0 || c.savedHighMs < 0.0;
  const std::string verdict = !decided ? "made no difference the frames can resolve"
                              : c.savedMs > 0.0 ? fmt::format("saved {:.4f} ms", c.savedMs)
                                                : fmt::format("cost {:.4f} ms", -c.savedMs);
  return fmt::format(
      "async compute {} ({:+.4f}..{:+.4f} ms, 95%): frame {:.4f} ms on one queue against {:.4f} ms on {} queues "
      "(render.async=0 against 1, {} frames against the measured ones); the queues overlapped {:.4f} ms per frame",
      verdict, c.savedLowMs, c.savedHighMs, c.singleQueueFrame.median, c.asyncFrame.median, c.queues,
      c.singleQueueMs.size(), c.overlapMs);
}

}  // namespace fgb::harness
