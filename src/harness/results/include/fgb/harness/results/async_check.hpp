// What async compute bought: the measured frames (render.async=1) against frames of the same run
// with every pass on the graphics queue (render.async=0, the graph compiled again), and how long
// the queues overlapped. Plain data and arithmetic; the run room measures the frames.
#pragma once

#include <cstdint>
#include <fgb/harness/stats/stats.hpp>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

namespace fgb::harness {

// One pass of one frame on the device's timeline: its queue and its begin and end (ms in the frame).
struct PassInterval {
  std::string queue;
  double beginMs = 0.0;
  double endMs = 0.0;
};

// Time in a frame during which at least two queues were busy (each queue's passes as one union).
double queueOverlapMs(std::span<const PassInterval> passes);
// Time in a frame of span `spanMs` during which no pass ran on any queue: barriers, submit
// boundaries and semaphore waits between passes.
double idleGapsMs(std::span<const PassInterval> passes, double spanMs);

struct AsyncComparison {
  uint32_t queues = 0;         // queues the measured frames' graph ran on
  std::string skipped;         // why there was no comparison ("" when there was one)
  std::vector<double> singleQueueMs;  // frame spans with render.async=0
  std::vector<double> idleGapsMs;     // per single-queue frame
  Summary singleQueue;
  MedianInterval asyncFrame, singleQueueFrame;  // medians with their 95% intervals
  // singleQueue - async median, and bounds from the two intervals (each side's worst case).
  double savedMs = 0.0, savedLowMs = 0.0, savedHighMs = 0.0;
  double overlapMs = 0.0;  // median over the measured frames of the time both queues were busy
  double wallMs = 0.0;     // host time of the comparison: two compiles and the single-queue frames
  [[nodiscard]] bool compared() const { return !singleQueueMs.empty(); }
};

// The comparison from the measured frames' spans and overlaps and the single-queue frames.
AsyncComparison compareAsync(uint32_t queues, std::span<const double> asyncFramesMs,
                             std::span<const double> overlapsMs, std::vector<double> singleQueueMs,
                             std::vector<double> idleGapsMs);
// Why a run has no comparison: one queue, render.async=0 already, or skipped by option.
AsyncComparison skippedAsync(uint32_t queues, std::string why);

nlohmann::json toJson(const AsyncComparison& comparison);
// The terminal's and report's sentence, e.g. "async compute saved 0.048 ms (0.031..0.060) of
// 1.016 ms: the queues overlapped 0.162 ms per frame".
std::string describeAsync(const AsyncComparison& comparison);

}  // namespace fgb::harness
