#include <fgb/harness/run/run_loop.hpp>

#include <fgb/core/error.hpp>
#include <fgb/core/knob_registry.hpp>

#include <chrono>
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
    if (inserted) run.passes.push_back(PassRecord{pass.name, pass.queue, pass.culled, {}, {}, {}, false, {}});
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
  if (frame.pathTimeS >= 0.0) run.framePathTimeS.push_back(frame.pathTimeS);
}

void finalizeColumns(RunResult& run) {
  for (auto& pass : run.passes) {
    pass.samplesMs.resize(run.frameGpuMs.size(), 0.0);
    if (!pass.startMs.empty()) pass.startMs.resize(run.frameGpuMs.size(), 0.0);
    if (pass.culled) pass.samplesMs.clear();
  }
}

}  // namespace

RunResult runBenchmark(render::Workload& workload, const RunOptions& options) {
  const uint32_t total = options.warmup + options.frames;
  std::vector<render::FrameTiming> timings;
  timings.reserve(total);
  double workloadMs = 0.0;

  const auto loopStart = Clock::now();
  for (uint32_t i = 0; i < total; ++i) {
    const auto before = Clock::now();
    render::FrameTiming timing = workload.renderFrame();
    workloadMs += millisecondsBetween(before, Clock::now());
    if (hasTimings(timing)) timings.push_back(std::move(timing));
    if (options.progress) options.progress(i + 1, total);
  }
  const auto beforeFinish = Clock::now();
  for (auto& late : workload.finish()) {
    if (hasTimings(late)) timings.push_back(std::move(late));
  }
  const auto loopEnd = Clock::now();
  workloadMs += millisecondsBetween(beforeFinish, loopEnd);

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

  run.overhead.loopWallMs = millisecondsBetween(loopStart, loopEnd);
  run.overhead.workloadCallsMs = workloadMs;
  run.overhead.harnessMs = std::max(0.0, run.overhead.loopWallMs - workloadMs);
  run.overhead.perFrameUs = total ? run.overhead.harnessMs * 1000.0 / total : 0.0;
  return run;
}

std::map<std::string, std::string> parseKnobs(const std::vector<std::string>& assignments) {
  return splitKnobAssignments(assignments);
}

}  // namespace fgb::harness
