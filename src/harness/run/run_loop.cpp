#include <algorithm>
#include <chrono>
#include <fgb/core/error.hpp>
#include <fgb/core/knob_registry.hpp>
#include <fgb/harness/run/device_probe.hpp>
#include <fgb/harness/run/run_loop.hpp>
#include <map>

namespace fgb::harness {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

bool hasTimings(const render::FrameTiming& t) { return !t.passes.empty(); }

// Per-pass sample columns in first-seen (declaration) order.
void appendFrame(RunResult& run, std::map<std::string, std::size_t>& index, const render::FrameTiming& frame) {
  const std::size_t frameNumber = run.frameGpuMs.size();
  for (const auto& pass : frame.passes) {
    auto [it, inserted] = index.try_emplace(pass.name, run.passes.size());
    if (inserted) run.passes.push_back(passRecord(pass.name, pass.queue, pass.culled));
    PassRecord& record = run.passes[it->second];
    record.culled = record.culled && pass.culled;  // culled only if culled in every frame
    // Keep columns aligned with frames even if a pass first appears late.
    record.samplesMs.resize(frameNumber, 0.0);
    record.samplesMs.push_back(pass.culled ? 0.0 : pass.gpuMs);
    if (pass.gpuStartMs >= 0.0) {
      record.startMs.resize(frameNumber, 0.0);
      record.startMs.push_back(pass.gpuStartMs);
    }
  }
  run.frameGpuMs.push_back(frame.gpuFrameMs);
  run.frameCpuMs.push_back(frame.cpuFrameMs);
  run.frameSubmitMs.push_back(frame.submitMs);
  run.nodesRecorded.push_back(frame.nodesRecorded);
  run.nodesReused.push_back(frame.nodesReused);
  if (frame.pathTimeS >= 0.0) run.framePathTimeS.push_back(frame.pathTimeS);
}

void finalizeColumns(RunResult& run) {
  for (auto& pass : run.passes) {
    pass.samplesMs.resize(run.frameGpuMs.size(), 0.0);
    if (!pass.startMs.empty()) pass.startMs.resize(run.frameGpuMs.size(), 0.0);
    if (pass.culled) pass.samplesMs.clear();
  }
}

std::vector<FrameClock> frameClocks(const std::vector<render::FrameTiming>& measured) {
  std::vector<FrameClock> clocks;
  for (const auto& frame : measured) clocks.push_back({frame.gpuFrameMs, frame.gpuFrameStartMs, frame.cpuFrameMs + frame.submitMs});
  return clocks;
}

}  // namespace

RunResult runBenchmark(render::Workload& workload, const RunOptions& options) {
  const uint32_t total = options.warmup + options.frames;
  std::vector<render::FrameTiming> timings;
  timings.reserve(total);
  double workloadMs = 0.0;
  const auto collect = [&](std::vector<render::FrameTiming> late) {
    for (auto& timing : late) {
      if (hasTimings(timing)) timings.push_back(std::move(timing));
    }
  };
  const auto render = [&](uint32_t frame) {
    const auto before = Clock::now();
    render::FrameTiming timing = workload.renderFrame();
    workloadMs += millisecondsBetween(before, Clock::now());
    if (hasTimings(timing)) timings.push_back(std::move(timing));
    if (options.progress) options.progress(frame + 1, total);
  };

  const DeviceProbe probe(workload.device());
  const auto loopStart = Clock::now();
  for (uint32_t i = 0; i < options.warmup; ++i) render(i);
  // The measured frames start on an idle device and end with one wait: their wall time per frame
  // is the throughput the spans are checked against (frames in flight may overlap on the GPU).
  collect(workload.finish());
  const std::optional<DeviceSample> startState = probe.sample();
  const auto measureStart = Clock::now();
  for (uint32_t i = options.warmup; i < total; ++i) render(i);
  const auto beforeFinish = Clock::now();
  collect(workload.finish());
  const auto loopEnd = Clock::now();
  workloadMs += millisecondsBetween(beforeFinish, loopEnd);
  const std::optional<DeviceSample> endState = probe.sample();

  if (timings.size() < total) {
    throw DeviceError("the workload returned timings for " + std::to_string(timings.size()) + " of " +
                      std::to_string(total) + " rendered frames");
  }

  RunResult run;
  run.device = workload.device();
  run.stats = workload.stats();
  run.nonFinite = workload.nonFiniteCounts();
  run.checkedFinite = !run.nonFinite.empty();  // --check-finite always checks at least the HDR image
  std::map<std::string, std::size_t> index;
  for (std::size_t i = options.warmup; i < options.warmup + options.frames; ++i) appendFrame(run, index, timings[i]);
  for (const auto& counts : run.nonFinite) {
    for (auto& pass : run.passes)
      if (pass.name == counts.pass) pass.nonFinite = counts;
  }
  finalizeColumns(run);
  summarizeRun(run, options.unstableSpread);
  run.deviceState.source = probe.available() ? "nvml" : "";
  run.deviceState.unavailable = probe.unavailable();
  run.deviceState.start = startState;
  run.deviceState.end = endState;
  const std::vector<render::FrameTiming> measured(timings.begin() + options.warmup, timings.begin() + total);
  run.wallClock = checkWallClock(frameClocks(measured), millisecondsBetween(measureStart, loopEnd), run.deviceState);

  run.overhead.loopWallMs = millisecondsBetween(loopStart, loopEnd);
  run.overhead.workloadCallsMs = workloadMs;
  run.overhead.harnessMs = std::max(0.0, run.overhead.loopWallMs - workloadMs);
  run.overhead.perFrameUs = total ? run.overhead.harnessMs * 1000.0 / total : 0.0;
  return run;
}

uint32_t defaultIsolatedFrames(uint32_t frames) {
  return std::clamp(frames / 4, 3u, 16u);
}

void calibrateIsolated(render::Workload& workload, RunResult& run, uint32_t frames) {
  const auto start = Clock::now();
  std::vector<render::FrameTiming> isolated;
  for (uint32_t i = 0; i < frames; ++i) {
    render::FrameTiming timing = workload.renderIsolatedFrame();
    if (!hasTimings(timing)) break;  // the workload cannot isolate passes
    isolated.push_back(std::move(timing));
  }
  run.overhead.calibrationMs = millisecondsBetween(start, Clock::now());
  if (isolated.empty()) return;
  run.isolatedFrames = static_cast<uint32_t>(isolated.size());
  // Every frame lists every declared pass, in declaration order (FrameTiming): pass i is the
  // same pass in each, and the critical path takes its costs in that order.
  const auto& declared = isolated.front().passes;
  std::vector<double> costs;
  std::vector<PassRecord*> records;
  for (std::size_t i = 0; i < declared.size(); ++i) {
    std::vector<double> samples;
    for (const auto& frame : isolated) {
      if (i < frame.passes.size() && !frame.passes[i].culled) samples.push_back(frame.passes[i].gpuMs);
    }
    const Summary summary = summarize(samples);
    costs.push_back(summary.median);
    PassRecord* record = nullptr;
    for (auto& candidate : run.passes) {
      if (candidate.name == declared[i].name && !candidate.culled) record = &candidate;
    }
    records.push_back(record);
    if (record == nullptr) continue;
    record->isolatedMs = std::move(samples);
    record->isolated = summary;
  }
  const std::vector<double> shares = workload.criticalPathShares(costs);
  for (std::size_t i = 0; i < shares.size() && i < records.size(); ++i) {
    if (records[i] != nullptr) records[i]->criticalShare = shares[i];
  }
}

uint32_t defaultAsyncFrames(uint32_t frames) {
  return std::clamp(frames / 4, 8u, 32u);
}

namespace {

std::vector<PassInterval> intervalsOf(const render::FrameTiming& frame) {
  std::vector<PassInterval> intervals;
  for (const auto& pass : frame.passes) {
    if (!pass.culled && pass.gpuStartMs >= 0.0)
      intervals.push_back({pass.queue, pass.gpuStartMs, pass.gpuStartMs + pass.gpuMs});
  }
  return intervals;
}

// Per measured frame, the time at least two queues were busy (passes without start offsets are
// left out).
std::vector<double> measuredOverlaps(const RunResult& run) {
  std::vector<double> overlaps;
  for (std::size_t f = 0; f < run.frameGpuMs.size(); ++f) {
    std::vector<PassInterval> intervals;
    for (const auto& pass : run.passes) {
      if (f < pass.startMs.size() && f < pass.samplesMs.size())
        intervals.push_back({pass.queue, pass.startMs[f], pass.startMs[f] + pass.samplesMs[f]});
    }
    overlaps.push_back(queueOverlapMs(intervals));
  }
  return overlaps;
}

}  // namespace

void compareAsyncCompute(render::Workload& workload, RunResult& run, uint32_t frames) {
  const auto start = Clock::now();
  const uint32_t queues = workload.queuesUsed();
  if (queues < 2) {
    run.asyncCompute = skippedAsync(queues, "every pass ran on one queue: the device has one, or render.async=0");
    return;
  }
  if (!run.framePathTimeS.empty()) {
    run.asyncCompute = skippedAsync(queues, "a camera path: frames at other path times would not compare");
    return;
  }
  if (!workload.setAsyncCompute(false)) {
    run.asyncCompute = skippedAsync(queues, "the workload cannot compile its graph for one queue");
    return;
  }
  constexpr uint32_t kWarmup = 2;  // the recompiled graph's first frames record every node
  std::vector<render::FrameTiming> single;
  for (uint32_t i = 0; i < kWarmup + frames; ++i) {
    render::FrameTiming timing = workload.renderFrame();
    if (hasTimings(timing)) single.push_back(std::move(timing));
  }
  for (auto& timing : workload.finish()) {
    if (hasTimings(timing)) single.push_back(std::move(timing));
  }
  workload.setAsyncCompute(true);
  std::vector<double> spans, gaps;
  for (std::size_t i = std::min<std::size_t>(kWarmup, single.size()); i < single.size(); ++i) {
    spans.push_back(single[i].gpuFrameMs);
    gaps.push_back(idleGapsMs(intervalsOf(single[i]), single[i].gpuFrameMs));
  }
  run.asyncCompute = compareAsync(queues, run.frameGpuMs, measuredOverlaps(run), std::move(spans), std::move(gaps));
  run.asyncCompute.wallMs = millisecondsBetween(start, Clock::now());
}

std::map<std::string, std::string> parseKnobs(const std::vector<std::string>& assignments) {
  return splitKnobAssignments(assignments);
}

}  // namespace fgb::harness
