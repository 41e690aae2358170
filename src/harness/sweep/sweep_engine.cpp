// runSweep: references, interleaved measuring rounds, comparison with the references, the front.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fgb/harness/sweep/sweep.hpp>
#include <memory>
#include <numeric>
#include <random>

namespace fgb::harness {
namespace {

bool bitIdentical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

// The images of frame `frames` of a freshly opened workload, and where its time went.
RenderedImages renderImagesAfter(const WorkloadOpener& open, const render::WorkloadConfig& config, uint32_t frames,
                                 ReferenceRenderWall& wall) {
  Stopwatch timer;
  ConfigurationRenderer renderer(open, config);
  wall.openMs = timer.lap();
  renderer.warmUp(std::max(frames, 1u));
  wall.framesMs = timer.lap();
  RenderedImages images = renderer.readImages();
  wall.readbackMs = timer.lap();
  return images;
}

// One render of `workload` compared with the reference's images.
ReferenceCheck renderCheck(const WorkloadOpener& open, const ReferenceOutcome& reference, std::string label,
                           const render::WorkloadConfig& workload, uint32_t frames) {
  ReferenceCheck check;
  check.label = std::move(label);
  check.workload = workload;
  const RenderedImages images = renderImagesAfter(open, workload, frames, check.wall);
  if (images.display.width != reference.images.display.width ||
      images.display.height != reference.images.display.height) {
    throw DeviceError(fmt::format("{}: rendered {} but the reference {}", check.label, describeSize(images.display),
                                  describeSize(reference.images.display)));
  }
  check.display = compareImages(quantizeToSrgb8(reference.images.display), quantizeToSrgb8(images.display)).metrics;
  check.hdr = compareImages(reference.images.hdr, images.hdr).metrics;
  return check;
}

std::size_t referenceIndex(std::vector<render::WorkloadConfig>& references, const render::WorkloadConfig& wanted) {
  for (std::size_t i = 0; i < references.size(); ++i) {
    if (sameWorkload(references[i], wanted)) return i;
  }
  references.push_back(wanted);
  return references.size() - 1;
}

// One visit of a configuration: up to `frames` measured frames after plan.rewarmFrames dropped
// ones. Where checkEvery is set (until-stable on a CPU device, SweepPlan::trimOnCpu), the visit
// measures that many frames at a time and ends as soon as the configuration is stable. Returns the
// frames measured.
uint32_t measureVisit(ConfigurationRenderer& renderer, uint32_t frames, const SweepPlan& plan, uint32_t checkEvery) {
  const uint32_t step = plan.untilStable && checkEvery > 0 ? checkEvery : frames;
  uint32_t measured = 0;
  while (measured < frames) {
    const uint32_t chunk = std::min(step, frames - measured);
    renderer.measure(chunk, measured == 0 ? plan.rewarmFrames : 0);
    measured += chunk;
    if (plan.untilStable && isStable(renderer.result(), *plan.untilStable)) break;
  }
  return measured;
}

bool finished(const RunResult& run, const SweepPlan& plan) {
  if (run.frameGpuMs.size() >= plan.frames) return true;
  return plan.untilStable && isStable(run, *plan.untilStable);
}

// Measures every configuration in rounds: each round visits the unfinished configurations in a
// random order (seeded), `roundFrames` frames each, so slow drift (thermal, other processes)
// spreads over all configurations alike instead of favouring whichever ran first.
void measureInRounds(std::vector<std::unique_ptr<ConfigurationRenderer>>& renderers, SweepResult& result,
                     const SweepPlan& plan, uint32_t checkEvery, const SweepProgress& progress,
                     const Stopwatch& sweepClock) {
  std::mt19937_64 random(plan.seed);
  const uint32_t planned = plan.frames * static_cast<uint32_t>(renderers.size());
  uint32_t done = 0;
  result.stopReason = plan.untilStable ? "stable" : "frames";
  while (true) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < renderers.size(); ++i) {
      if (!finished(renderers[i]->result(), plan)) order.push_back(i);
    }
    if (order.empty()) break;
    if (plan.maxMinutes > 0 && result.rounds > 0 && sweepClock.elapsedMs() > plan.maxMinutes * 60000.0) {
      result.stopReason = "time limit";
      break;
    }
    std::shuffle(order.begin(), order.end(), random);
    for (std::size_t i : order) {
      // The time limit also ends a round early (after the first round): a round of slow
      // configurations on a CPU device can take minutes.
      if (plan.maxMinutes > 0 && result.rounds > 0 && sweepClock.elapsedMs() > plan.maxMinutes * 60000.0) break;
      const uint32_t have = static_cast<uint32_t>(renderers[i]->result().frameGpuMs.size());
      const uint32_t frames = std::min(plan.roundFrames, plan.frames - have);
      Stopwatch visit;
      const uint32_t measured = measureVisit(*renderers[i], frames, plan, checkEvery);
      ConfigurationWall& wall = result.configurations[i].wall;
      wall.measureMs += visit.elapsedMs();
      wall.rewarmFrames += plan.rewarmFrames;
      ++wall.visits;
      done += measured;
      if (progress.frames) progress.frames(std::min(done, planned), planned);
    }
    ++result.rounds;
  }
}

// The plan as the opened device wants it (CPU devices: until-stable by default, and with trimOnCpu
// no frames beyond need), recorded in the result. Returns the frames between stability checks
// within a visit (0: once per visit).
uint32_t adaptToDevice(SweepPlan& plan, SweepResult& result) {
  const bool cpu = result.device.type == "cpu";
  if (!plan.untilStable && plan.untilStableOnCpu && cpu) plan.untilStable = plan.cpuStabilityRule;
  uint32_t checkEvery = 0;
  if (cpu && plan.trimOnCpu) {
    plan.rewarmFrames = 0;
    checkEvery = plan.cpuStableCheckFrames;
    if (plan.trimWarmupOnCpu) plan.warmup = std::max(plan.imageFrame, 1u);
  }
  result.warmupFrames = std::max({plan.imageFrame, plan.warmup, 1u});
  result.rewarmFrames = plan.rewarmFrames;
  result.stableCheckFrames = plan.untilStable ? (checkEvery ? checkEvery : plan.roundFrames) : 0;
  if (plan.untilStable) plan.frames = plan.stableFrameCap;  // from here on `frames` is the cap
  result.untilStable = plan.untilStable;
  result.frameCap = plan.frames;
  return checkEvery;
}

}  // namespace

bool sameWorkload(const render::WorkloadConfig& a, const render::WorkloadConfig& b) {
  return a.scenePath == b.scenePath && a.device == b.device && a.width == b.width && a.height == b.height &&
         a.msaa == b.msaa && a.clampMsaaToPath == b.clampMsaaToPath && a.validation == b.validation &&
         a.knobs == b.knobs && a.cacheDir == b.cacheDir;
}

ReferenceOutcome renderReference(const WorkloadOpener& open, const render::WorkloadConfig& config, uint32_t frames) {
  Stopwatch timer;
  ReferenceOutcome ref;
  ref.workload = config;
  ref.renders.resize(2);
  ref.images = renderImagesAfter(open, config, frames, ref.renders[0]);
  // Its noise floor: a second render of the same reference, compared with the first.
  const RenderedImages again = renderImagesAfter(open, config, frames, ref.renders[1]);
  if (again.hdr.width != ref.images.hdr.width || again.hdr.height != ref.images.hdr.height) {
    throw DeviceError("two renders of the reference differ in size");
  }
  ref.identical = bitIdentical(ref.images.hdr, again.hdr) && bitIdentical(ref.images.display, again.display);
  ref.repeatDisplay = compareImages(quantizeToSrgb8(ref.images.display), quantizeToSrgb8(again.display)).metrics;
  ref.repeatHdr = compareImages(ref.images.hdr, again.hdr).metrics;
  ref.renderMs = timer.elapsedMs();
  return ref;
}

void checkReference(const WorkloadOpener& open, ReferenceOutcome& reference, const SweepPlan& plan,
                    const std::vector<const SweepConfiguration*>& configurations, uint32_t frames,
                    const std::function<void(const std::string&)>& say) {
  if (const auto step = convergenceStepOf(reference.workload)) {
    const std::string label = "render.ssaa=" + step->knobs.at("render.ssaa");
    if (say) say("convergence (" + label + ")");
    reference.convergence = renderCheck(open, reference, label, *step, frames);
  }
  for (const SweepConfiguration* c : configurations) {
    const std::string label = biasLabelOf(*c, plan.referenceRules);
    if (label.empty() || reference.biasIndex(label)) continue;
    if (say) say("bias of " + label);
    reference.biases.push_back(
        renderCheck(open, reference, label, *biasRenderOf(*c, reference.workload, plan.referenceRules), frames));
  }
}

SweepResult runSweep(const WorkloadOpener& open, const SweepPlan& requested, const SweepProgress& progress) {
  Stopwatch sweepClock, phase;
  SweepPlan plan = requested;
  SweepResult result;
  result.scene = plan.scene;
  result.sceneHash = sceneHash(plan.scene);
  result.alpha = plan.alpha;
  result.seed = plan.seed;
  result.pathTimes = plan.pathTimes;
  auto say = [&](const std::string& what) {
    if (progress.phase) progress.phase(what);
  };

  // Every configuration is opened first: a bad knob fails here, before the costly references (and
  // before anything is said, so that bad input gets its one line).
  std::vector<std::unique_ptr<ConfigurationRenderer>> renderers;
  for (const auto& c : plan.configurations) {
    renderers.push_back(std::make_unique<ConfigurationRenderer>(open, c.workload));
    ConfigurationOutcome outcome;
    outcome.configuration = c;
    outcome.wall.openMs = renderers.back()->result().overhead.openMs;
    result.configurations.push_back(std::move(outcome));
  }
  result.overhead.openMs = phase.lap();
  if (!renderers.empty()) result.device = renderers.front()->result().device;
  const uint32_t checkEvery = adaptToDevice(plan, result);

  result.referenceRules = plan.referenceRules;
  if (!plan.configurations.empty()) {
    for (const auto& [key, value] : plan.configurations.front().point)
      result.roles[key] = referenceRoleName(roleOf(plan.referenceRules, key));
  }
  result.lookKeys =
      plan.referenceOverride ? std::vector<std::string>{} : variedLookKeys(plan.configurations, plan.referenceRules);
  std::vector<render::WorkloadConfig> referenceConfigs;
  for (auto& c : result.configurations) {
    c.reference = referenceIndex(referenceConfigs,
                                 plan.referenceOverride.value_or(referenceOf(c.configuration, plan.referenceRules)));
  }
  for (std::size_t r = 0; r < referenceConfigs.size(); ++r) {
    say(fmt::format("reference {}/{} (2 renders)", r + 1, referenceConfigs.size()));
    result.references.push_back(renderReference(open, referenceConfigs[r], plan.imageFrame));
    if (plan.referenceOverride) continue;
    std::vector<const SweepConfiguration*> sharing;
    for (const auto& c : result.configurations)
      if (c.reference == r) sharing.push_back(&c.configuration);
    checkReference(open, result.references.back(), plan, sharing, plan.imageFrame, [&](const std::string& what) {
      say(fmt::format("reference {}/{}: {}", r + 1, referenceConfigs.size(), what));
    });
  }
  for (auto& c : result.configurations)
    c.bias = result.references[c.reference].biasIndex(biasLabelOf(c.configuration, plan.referenceRules));
  result.overhead.referenceMs = phase.lap();

  say("warming up");
  for (std::size_t i = 0; i < renderers.size(); ++i) {
    Stopwatch warming;
    ConfigurationOutcome& c = result.configurations[i];
    renderers[i]->warmUp(std::max(plan.imageFrame, 1u));
    c.images = renderers[i]->readImages();
    if (plan.warmup > plan.imageFrame) renderers[i]->warmUp(plan.warmup - plan.imageFrame);
    c.wall.warmupFrames = std::max({plan.imageFrame, plan.warmup, 1u});
    c.wall.warmupMs = warming.elapsedMs();
  }
  result.overhead.warmupMs = phase.lap();

  say("measuring");
  measureInRounds(renderers, result, plan, checkEvery, progress, sweepClock);
  for (std::size_t i = 0; i < renderers.size(); ++i) {
    renderers[i]->checkValidation();
    ConfigurationOutcome& c = result.configurations[i];
    c.run = renderers[i]->result();
    c.frameGpu = medianConfidenceInterval(c.run.frameGpuMs);
    c.stable = plan.untilStable && isStable(c.run, *plan.untilStable);
  }
  if (result.stopReason == "stable") {
    for (const auto& c : result.configurations) {
      if (!c.stable) result.stopReason = "frame cap (not every configuration stable)";
    }
  }
  result.overhead.measureMs = phase.lap();
  renderers.clear();  // every device closed before the metrics (memory)
  result.overhead.closeMs = phase.lap();

  judgeAlongPath(open, plan, result, say);
  say("comparing with the reference");
  compareWithReferences(result);
  markFront(result);
  result.overhead.metricsMs = phase.lap();
  result.overhead.totalMs = sweepClock.elapsedMs();
  return result;
}

void compareWithReferences(SweepResult& result) {
  result.errorFloor = 0.0;
  for (const auto& ref : result.references) {
    if (ref.repeatDisplay.flip) result.errorFloor = std::max(result.errorFloor, ref.repeatDisplay.flip->mean);
  }
  for (auto& c : result.configurations) {
    Stopwatch timer;
    const ReferenceOutcome& ref = result.references.at(c.reference);
    if (c.images.display.width != ref.images.display.width || c.images.display.height != ref.images.display.height) {
      throw DeviceError(fmt::format("{}: rendered {} but its reference {}", c.configuration.label,
                                    describeSize(c.images.display), describeSize(ref.images.display)));
    }
    // LDR-FLIP on the display images as frame.png stores them (8-bit sRGB), HDR-FLIP on the HDR.
    const Comparison display = compareImages(quantizeToSrgb8(ref.images.display), quantizeToSrgb8(c.images.display));
    c.display = display.metrics;
    c.heatMap = heatMap(display.errorMap, display.nonFiniteMask, c.images.display.width, c.images.display.height);
    c.hdr = compareImages(ref.images.hdr, c.images.hdr).metrics;
    c.unresolved = ref.convergence && sweepError(c) <= kUnresolvedGapFactor * ref.convergenceGap();
    c.wall.metricsMs = timer.elapsedMs();
  }
}

std::optional<std::size_t> ReferenceOutcome::biasIndex(const std::string& label) const {
  const auto it = std::find_if(biases.begin(), biases.end(), [&](const ReferenceCheck& b) { return b.label == label; });
  if (label.empty() || it == biases.end()) return std::nullopt;
  return static_cast<std::size_t>(it - biases.begin());
}

std::vector<double> spreadPathTimes(double durationS, uint32_t count) {
  std::vector<double> times;
  if (!(durationS > 0.0)) return times;
  for (uint32_t k = 0; k < count; ++k) times.push_back(std::round((k + 0.5) * durationS / count * 1000.0) / 1000.0);
  return times;
}

render::WorkloadConfig atPathTime(render::WorkloadConfig config, double timeS) {
  config.knobs["camera.time"] = fmt::format("{}", timeS);
  return config;
}

void judgeAlongPath(const WorkloadOpener& open, const SweepPlan& plan, SweepResult& result,
                    const std::function<void(const std::string&)>& say) {
  if (plan.pathTimes.empty()) return;
  const auto tell = [&](const std::string& what) {
    if (say) say(what);
  };
  // The references first, each image kept: every configuration sharing one compares with it.
  for (std::size_t r = 0; r < result.references.size(); ++r) {
    ReferenceOutcome& ref = result.references[r];
    tell(fmt::format("reference {}/{} at {} path times", r + 1, result.references.size(), plan.pathTimes.size()));
    ref.pathImages.clear();
    for (double t : plan.pathTimes) {
      ReferenceRenderWall wall;
      ref.pathImages.push_back(renderImagesAfter(open, atPathTime(ref.workload, t), plan.imageFrame, wall));
    }
  }
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    ConfigurationOutcome& c = result.configurations[i];
    tell(fmt::format("configuration {}/{} at {} path times", i + 1, result.configurations.size(),
                     plan.pathTimes.size()));
    const ReferenceOutcome& ref = result.references.at(c.reference);
    c.pathErrors.clear();
    for (std::size_t k = 0; k < plan.pathTimes.size(); ++k) {
      ReferenceRenderWall wall;
      const RenderedImages images =
          renderImagesAfter(open, atPathTime(c.configuration.workload, plan.pathTimes[k]), plan.imageFrame, wall);
      const RenderedImages& want = ref.pathImages.at(k);
      if (images.display.width != want.display.width || images.display.height != want.display.height) {
        throw DeviceError(fmt::format("{}: rendered {} but its reference {}", c.configuration.label,
                                      describeSize(images.display), describeSize(want.display)));
      }
      PathTimeError e;
      e.timeS = plan.pathTimes[k];
      e.display = compareImages(quantizeToSrgb8(want.display), quantizeToSrgb8(images.display)).metrics;
      e.hdr = compareImages(want.hdr, images.hdr).metrics;
      c.pathErrors.push_back(std::move(e));
    }
  }
}

double ConfigurationOutcome::pathErrorMean() const {
  double sum = 0.0;
  for (const PathTimeError& e : pathErrors) sum += displayError(e.display);
  return pathErrors.empty() ? 0.0 : sum / double(pathErrors.size());
}

double ConfigurationOutcome::pathErrorWorst() const {
  double worst = 0.0;
  for (const PathTimeError& e : pathErrors) worst = std::max(worst, displayError(e.display));
  return worst;
}

double ConfigurationOutcome::pathErrorWorstTime() const {
  double worst = -1.0, at = 0.0;
  for (const PathTimeError& e : pathErrors) {
    if (displayError(e.display) > worst) {
      worst = displayError(e.display);
      at = e.timeS;
    }
  }
  return at;
}

double sweepError(const ConfigurationOutcome& c) {
  return c.pathErrors.empty() ? displayError(c.display) : c.pathErrorMean();
}

std::vector<std::string> viewKeys(const SweepResult& result) {
  std::vector<std::string> keys;
  for (const SweepAxis& axis : result.axes) {
    const auto role = result.roles.find(axis.key);
    if (role != result.roles.end() && role->second == referenceRoleName(ReferenceRole::Content))
      keys.push_back(axis.key);
  }
  return keys;
}

std::string viewOf(const SweepResult& result, const ConfigurationOutcome& configuration) {
  std::string view;
  for (const std::string& key : viewKeys(result)) {
    for (const auto& [axis, value] : configuration.configuration.point) {
      if (axis == key) view += (view.empty() ? "" : " ") + key + "=" + value;
    }
  }
  return view;
}

void markFront(SweepResult& result) {
  std::map<std::string, std::vector<std::size_t>> views;  // view -> its configurations
  for (std::size_t i = 0; i < result.configurations.size(); ++i) {
    const auto& c = result.configurations[i];
    if (c.run.frameGpuMs.empty()) throw DeviceError(c.configuration.label + ": no frames measured");
    views[viewOf(result, c)].push_back(i);
  }
  for (const auto& [view, members] : views) {
    std::vector<TradeoffPoint> points;
    for (const std::size_t i : members)
      points.push_back({result.configurations[i].run.frameGpuMs, sweepError(result.configurations[i])});
    const FrontAnalysis front = paretoFront(points, {result.alpha, result.errorFloor});
    for (std::size_t k = 0; k < members.size(); ++k) {
      auto& c = result.configurations[members[k]];
      c.onFront = front.onFront[k];
      c.dominatedBy.clear();
      for (const std::size_t d : front.dominatedBy[k]) c.dominatedBy.push_back(members[d]);
    }
  }
}

}  // namespace fgb::harness
