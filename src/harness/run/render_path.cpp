#include <fmt/format.h>

#include <algorithm>
#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/harness/run/render_path.hpp>
#include <fgb/harness/run/run_loop.hpp>
#include <map>
#include <string>

namespace fgb::harness {
namespace {

PassRecord& passNamed(RunResult& run, const PassRecord& like, std::size_t framesBefore) {
  for (auto& p : run.passes) {
    if (p.name == like.name) return p;
  }
  // A pass first seen now did not run in the earlier frames: culled there, so it is culled overall
  // only if it is culled now too.
  run.passes.push_back(passRecord(like.name, like.queue, like.culled));
  run.passes.back().samplesMs.assign(framesBefore, 0.0);
  return run.passes.back();
}

// The frames rendered so far and planned in all: a progress callback over several measuring calls.
ProgressCallback offsetProgress(const ProgressCallback& progress, uint32_t doneBefore, uint32_t planned) {
  if (!progress) return {};
  return [=](uint32_t done, uint32_t) { progress(doneBefore + done, planned); };
}

uint32_t measuredFrames(const RunResult& run) {
  return static_cast<uint32_t>(run.frameGpuMs.size());
}

}  // namespace

bool isStable(const RunResult& run, const StabilityRule& rule) {
  if (run.frameGpuMs.size() < rule.minFrames) return false;
  return medianConfidenceInterval(run.frameGpuMs).relativeHalfWidth() <= rule.relativeHalfWidth;
}

void appendMeasurements(RunResult& total, const RunResult& round) {
  const std::size_t before = total.frameGpuMs.size();
  const std::size_t after = before + round.frameGpuMs.size();
  total.device = round.device;
  total.stats = round.stats;
  for (const auto& p : round.passes) {
    PassRecord& t = passNamed(total, p, before);
    t.culled = t.culled && p.culled;
    if (p.nonFinite) t.nonFinite = p.nonFinite;  // --check-finite: the latest frame's counts
    t.samplesMs.resize(before, 0.0);  // a pass culled so far has no samples yet
    if (p.culled) {
      t.samplesMs.resize(after, 0.0);
    } else {
      t.samplesMs.insert(t.samplesMs.end(), p.samplesMs.begin(), p.samplesMs.end());
    }
    if (!p.startMs.empty()) {
      t.startMs.resize(before, 0.0);
      t.startMs.insert(t.startMs.end(), p.startMs.begin(), p.startMs.end());
    }
  }
  for (auto& t : total.passes) {
    t.samplesMs.resize(after, 0.0);
    if (!t.startMs.empty()) t.startMs.resize(after, 0.0);
    if (t.culled) t.samplesMs.clear();
  }
  if (round.checkedFinite) {
    total.checkedFinite = true;
    total.nonFinite = round.nonFinite;
  }
  total.frameGpuMs.insert(total.frameGpuMs.end(), round.frameGpuMs.begin(), round.frameGpuMs.end());
  total.frameCpuMs.insert(total.frameCpuMs.end(), round.frameCpuMs.begin(), round.frameCpuMs.end());
  for (auto [to, from] :
       {std::pair{&total.frameSubmitMs, &round.frameSubmitMs}, std::pair{&total.nodesRecorded, &round.nodesRecorded},
        std::pair{&total.nodesReused, &round.nodesReused}}) {
    to->insert(to->end(), from->begin(), from->end());
  }
  total.framePathTimeS.insert(total.framePathTimeS.end(), round.framePathTimeS.begin(), round.framePathTimeS.end());
  HarnessOverhead& o = total.overhead;
  o.loopWallMs += round.overhead.loopWallMs;
  o.workloadCallsMs += round.overhead.workloadCallsMs;
  o.harnessMs += round.overhead.harnessMs;
  o.perFrameUs = after ? o.harnessMs * 1000.0 / static_cast<double>(after) : 0.0;
  appendWallClock(total.wallClock, total.deviceState, round.wallClock, round.deviceState, total.frameGpuMs,
                  total.frameCpuMs);
  summarizeRun(total);
}

ConfigurationRenderer::ConfigurationRenderer(const WorkloadOpener& open, const render::WorkloadConfig& config)
    : config_(config) {
  Stopwatch opening;
  workload_ = open(config_);
  run_.overhead.openMs = opening.elapsedMs();
  run_.overhead.startup = workload_->startup();
  run_.device = workload_->device();
}

void ConfigurationRenderer::warmUp(uint32_t frames, const ProgressCallback& progress) {
  if (frames == 0) return;
  runBenchmark(*workload_, RunOptions{frames, 0, kDefaultUnstableSpread, progress});
}

void ConfigurationRenderer::measure(uint32_t frames, uint32_t rewarm, const ProgressCallback& progress) {
  RunResult round = runBenchmark(*workload_, RunOptions{rewarm, frames, kDefaultUnstableSpread, progress});
  if (run_.frameGpuMs.empty() && run_.passes.empty()) {
    // The first measurement is taken as it is (what a single-round `run` reports), keeping the
    // start-up times measured when opening.
    round.overhead.openMs = run_.overhead.openMs;
    round.overhead.startup = run_.overhead.startup;
    run_ = std::move(round);
  } else {
    appendMeasurements(run_, round);
  }
}

void ConfigurationRenderer::checkValidation() const {
  if (workload_->validationMessages() > 0) {
    throw DeviceError(
        fmt::format("{} validation message(s) while rendering {}", workload_->validationMessages(), config_.scenePath));
  }
}

RenderedImages ConfigurationRenderer::readImages() {
  checkValidation();
  return {fromRendered(workload_->readHdr()), fromRendered(workload_->readDisplay())};
}

namespace {

// `request`'s configuration with `knobs` set, opened alone and rendered once: its display image.
Image renderOnce(const WorkloadOpener& open, const RenderRequest& request,
                 const std::map<std::string, std::string>& knobs) {
  render::WorkloadConfig config = request.workload;
  for (const auto& [key, value] : knobs) config.knobs[key] = value;
  ConfigurationRenderer still(open, config);
  still.warmUp(1);
  return still.readImages().display;
}

// The slowest path frames again, each opened alone as a still view at its path time: the frame it
// was (camera.time renders the same image the path does at that time).
std::vector<SlowFrame> renderSlowestFrames(const WorkloadOpener& open, const RenderRequest& request,
                                           const RunResult& run) {
  std::vector<SlowFrame> frames;
  for (const std::size_t f : run.slowestFrames(request.slowestFrames)) {
    const double time = run.framePathTimeS[f];
    frames.push_back({f, time, renderOnce(open, request, {{"camera.time", fmt::format("{}", time)}})});
  }
  return frames;
}

// The last measured frame's view (at its path time along a camera path) with each debug view of the
// clusters the path drew: their LOD levels and the clusters themselves.
std::vector<DebugViewImage> renderDebugViews(const WorkloadOpener& open, const RenderRequest& request,
                                             const RunResult& run) {
  std::vector<DebugViewImage> views;
  for (const char* view : {"lod", "clusters"}) {
    std::map<std::string, std::string> knobs{{"debug.view", view}};
    if (!run.framePathTimeS.empty()) knobs["camera.time"] = fmt::format("{}", run.framePathTimeS.back());
    views.push_back({view, renderOnce(open, request, knobs)});
  }
  return views;
}

}  // namespace

RunArtifacts renderConfiguration(const WorkloadOpener& open, const RenderRequest& request) {
  ConfigurationRenderer renderer(open, request.workload);
  const uint32_t planned = request.warmup + request.frames;
  if (!request.untilStable) {
    renderer.measure(request.frames, request.warmup, request.progress);
  } else {
    // Until stable: a first batch of at least minFrames, then batches until the median's interval
    // is narrow enough or the cap (request.frames) is reached.
    const StabilityRule& rule = *request.untilStable;
    const uint32_t first = std::min(request.frames, std::max(rule.minFrames, rule.batchFrames));
    renderer.measure(first, request.warmup, offsetProgress(request.progress, 0, planned));
    while (measuredFrames(renderer.result()) < request.frames && !isStable(renderer.result(), rule)) {
      const uint32_t done = measuredFrames(renderer.result());
      renderer.measure(std::min(rule.batchFrames, request.frames - done), 0,
                       offsetProgress(request.progress, request.warmup + done, planned));
    }
  }
  renderer.checkValidation();

  RunArtifacts a;
  Stopwatch readback;
  a.images = renderer.readImages();
  if (request.workload.capture) {
    // The same frame as the images: before the calibration renders more.
    a.passes =
        makeCaptureSet(renderer.workload().capturedPasses(), renderer.workload().passGraph(), renderer.result().stats);
  }
  const double readbackMs = readback.elapsedMs();
  if (request.graphDumps) {
    a.graphBrief = renderer.workload().graphviz(render::GraphDetail::Brief);
    a.graphFull = renderer.workload().graphviz(render::GraphDetail::Full);
  }
  a.run = renderer.result();
  if (request.isolateFrames > 0) {
    calibrateIsolated(renderer.workload(), a.run, request.isolateFrames);
    renderer.checkValidation();
  }
  if (request.asyncFrames > 0) {
    compareAsyncCompute(renderer.workload(), a.run, request.asyncFrames);
    renderer.checkValidation();
  }
  a.run.overhead.readbackMs = readbackMs;
  a.run.scene = request.workload.scenePath;
  a.run.sceneHash = sceneHash(request.workload.scenePath);
  const auto msaa = a.run.stats.find("msaa");
  a.run.config = {a.images.hdr.width,
                  a.images.hdr.height,
                  msaa != a.run.stats.end() ? static_cast<uint32_t>(msaa->second) : request.workload.msaa,
                  measuredFrames(a.run),
                  request.warmup,
                  request.workload.knobs};
  if (request.slowestFrames > 0) a.slowest = renderSlowestFrames(open, request, a.run);
  if (request.debugViews && renderer.workload().drawsClusters()) a.debugViews = renderDebugViews(open, request, a.run);
  return a;
}

}  // namespace fgb::harness
