// The one path that renders a configuration (scene, device, size, MSAA, knobs) and returns its
// timings and images. `fgbench run`, `bless`, `sweep` and `stress` all go through it:
//
//   renderConfiguration(open, request)       open, warm up, measure (fixed frames or until stable),
//                                            read the images back: what run and bless need;
//   ConfigurationRenderer                    the same steps one at a time, for callers that keep
//                                            several configurations open and measure them in
//                                            interleaved rounds (sweep, stress).
//
// The harness never opens a Vulkan device itself: callers pass how to open a workload
// (render::openWorkload in the CLI, a fake in tests).
#pragma once

#include <cstdint>
#include <fgb/harness/results/timings.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/harness/stats/stats.hpp>
#include <fgb/renderer/workload.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace fgb::harness {

using WorkloadOpener = std::function<std::unique_ptr<render::Workload>(const render::WorkloadConfig&)>;

// When to stop sampling a configuration (`--until-stable`): once the 95% confidence interval of
// its median GPU frame time (medianConfidenceInterval) is within ±relativeHalfWidth of the median,
// after at least minFrames measured frames, sampling batchFrames at a time. The frame cap is the
// caller's (RenderRequest::frames, the sweep's per-configuration cap).
struct StabilityRule {
  double relativeHalfWidth = 0.02;
  uint32_t minFrames = 16;
  uint32_t batchFrames = 16;
};

// True when `run`'s frame GPU samples meet `rule` (the frame cap is the caller's to check).
bool isStable(const RunResult& run, const StabilityRule& rule);

using ProgressCallback = std::function<void(uint32_t done, uint32_t total)>;

struct RenderRequest {
  render::WorkloadConfig workload;
  uint32_t warmup = 8;
  uint32_t frames = 64;                      // measured frames; the cap when untilStable is set
  std::optional<StabilityRule> untilStable;  // sample until stable instead of exactly `frames`
  // Calibration frames after the images were read (each pass alone on an idle device: the
  // isolated costs and critical-path shares); 0 skips it.
  uint32_t isolateFrames = 0;
  // Then frames with every pass on the graphics queue, against the measured ones (what render.async
  // saved; only where the graph ran on two or more queues); 0 skips it.
  uint32_t asyncFrames = 0;
  bool graphDumps = false;                   // fill graphBrief / graphFull
  // Along a camera path: render this many of the slowest measured frames again, each alone at its
  // path time (camera.time=T, its particles simulated to T), for the report's thumbnails.
  uint32_t slowestFrames = 0;
  // On a path that draws clusters: the last frame's view again with debug.view=lod and =clusters
  // (the report's pictures of the LOD cut).
  bool debugViews = false;
  ProgressCallback progress;                 // after every frame: (rendered, planned); may be empty
};

// An open configuration. Measured frames accumulate over calls to measure(); each call ends with
// the workload's finish(), so its timings are complete when it returns.
class ConfigurationRenderer {
 public:
  // Opens the workload (its time goes to result().overhead.openMs and .startup).
  ConfigurationRenderer(const WorkloadOpener& open, const render::WorkloadConfig& config);

  // Renders `frames` frames whose timings are dropped.
  void warmUp(uint32_t frames, const ProgressCallback& progress = {});
  // Renders `frames` frames and appends their timings to result(); `rewarm` frames rendered first
  // are dropped (a configuration picked up again after others ran on the machine).
  void measure(uint32_t frames, uint32_t rewarm = 0, const ProgressCallback& progress = {});
  // The last rendered frame's images; DeviceError if validation reported anything so far.
  RenderedImages readImages();
  // DeviceError naming the scene when validation reported anything so far.
  void checkValidation() const;

  const RunResult& result() const { return run_; }
  render::Workload& workload() { return *workload_; }
  const render::WorkloadConfig& config() const { return config_; }

 private:
  render::WorkloadConfig config_;
  std::unique_ptr<render::Workload> workload_;
  RunResult run_;
};

// Opens the configuration, warms up, measures (exactly request.frames, or until stable within that
// cap), reads the images back and fills the result's device, stats, config (size from the image,
// MSAA as the device ran it), scene and scene hash. The caller adds its tool version, budget and
// golden verdicts.
RunArtifacts renderConfiguration(const WorkloadOpener& open, const RenderRequest& request);

// Appends `round`'s measured frames to `total` (passes matched by name, columns kept aligned with
// frames), adds up the loop overhead and refreshes the summaries.
void appendMeasurements(RunResult& total, const RunResult& round);

}  // namespace fgb::harness
