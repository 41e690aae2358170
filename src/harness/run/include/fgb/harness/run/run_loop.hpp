// The measurement loop: warm-up frames, then N measured frames, collecting per-pass GPU times and
// CPU frame times from a Workload. Independent of Vulkan (unit-tested with a fake Workload).
#pragma once

#include <fgb/harness/results/timings.hpp>
#include <fgb/renderer/workload.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace fgb::harness {

struct RunOptions {
  uint32_t warmup = 8;
  uint32_t frames = 64;
  double unstableSpread = kDefaultUnstableSpread;
  // Called after every rendered frame with (frames rendered, total to render); may be empty.
  std::function<void(uint32_t done, uint32_t total)> progress;
};

// Renders warmup + frames frames. Timings may arrive late (renderFrame returning a timing without
// passes means "none ready yet"; finish() returns the rest); the first `warmup` timings are
// dropped. Fills device, stats, passes, frame samples, summaries and the harness overhead; the
// caller fills scene, config and version. Throws DeviceError if the workload returned fewer
// timings than frames rendered.
RunResult runBenchmark(render::Workload& workload, const RunOptions& options);

// The calibration: `frames` frames with each pass alone on an idle device (after the measured
// frames and after the images were read: it renders frames of its own). Fills the passes'
// isolated samples and summaries, and their critical-path shares over the compiled schedule
// weighted by the isolated medians. Nothing when the workload cannot isolate passes.
void calibrateIsolated(render::Workload& workload, RunResult& run, uint32_t frames);

// The calibration frames of a run measuring `frames` frames: a quarter of them, 3 to 16.
uint32_t defaultIsolatedFrames(uint32_t frames);

// render.async measured: where the measured frames' graph ran on two or more queues, compiles it
// again with every pass on the graphics queue, renders 2 warm-up and `frames` measured frames,
// and compiles it back. Fills run.asyncCompute: the single-queue frames against the measured
// ones, the queues' overlap in the measured frames, and the single-queue frames' idle gaps.
void compareAsyncCompute(render::Workload& workload, RunResult& run, uint32_t frames);
// The single-queue frames of a run measuring `frames` frames: a quarter of them, 8 to 32.
uint32_t defaultAsyncFrames(uint32_t frames);

// "--set key=value" arguments as a map; a malformed one is InputError naming it.
std::map<std::string, std::string> parseKnobs(const std::vector<std::string>& assignments);

}  // namespace fgb::harness
