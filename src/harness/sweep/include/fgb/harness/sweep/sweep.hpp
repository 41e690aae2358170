// `fgbench sweep`: run time against error over a grid of configurations.
//
//   SweepGrid        the axes (--vary KEY=V1,V2 and bench/sweeps/*.json) and their full grid;
//   referenceOf      the reference configuration each grid point is compared with, from each knob's
//                    reference role in the knob registry (docs/sweep.md, "The reference");
//   runSweep         renders the references (twice: their noise floor; once more one SSAA step
//                    down: their convergence gap; and the cost-only knobs' converged renders: their
//                    bias), opens every configuration,
//                    measures them in interleaved rounds in a seeded random order, compares their
//                    frames with the reference and marks the Pareto front;
//   sweep outputs    sweep.json / .csv / .md / .html and the terminal table (sweep_report.hpp).
//
// Nothing here is specific to a sweep of many knobs: `stress` is a one-knob sweep whose reference
// is its baseline rung (SweepPlan::referenceOverride).
#pragma once

#include <fgb/core/knob_registry.hpp>
#include <fgb/harness/metrics/metrics.hpp>
#include <fgb/harness/run/render_path.hpp>
#include <fgb/harness/stats/pareto.hpp>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

// One axis of the grid: a key (msaa, width, height, size, or any --set knob) and its values.
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;
};

// "KEY=V1,V2,..." -> axis. Malformed text (no '=', empty key or value, repeated value, a value the
// key cannot take: msaa not 1|2|4|8, width/height not a positive integer, size not WxH) is
// InputError naming `--vary TEXT`.
SweepAxis parseVary(const std::string& text);

// A standard sweep file (bench/sweeps/*.json), schema 1:
//   {"schema": 1, "description": "...", "vary": [{"key": "msaa", "values": [1, 4]}, ...],
//    "set": {"key": "value"}, "width": 640, "height": 360}
// ("set", "width", "height" optional). Errors are InputError naming the file and field.
struct SweepFile {
  std::string description;
  std::vector<SweepAxis> axes;
  std::map<std::string, std::string> knobs;
  uint32_t width = 0, height = 0;
};
SweepFile loadSweepFile(const std::filesystem::path& path);

// Largest grid a sweep accepts (a typo such as msaa=1,2,4,8 x size=... x ... is caught early).
inline constexpr std::size_t kMaxSweepConfigurations = 256;

struct SweepConfiguration {
  std::string label;                                // "msaa=4 bloom.mips=2": the varied values
  std::vector<std::pair<std::string, std::string>>  // the varied values, in axis order
      point;
  render::WorkloadConfig workload;
};

// The full grid: every combination of the axes' values applied to `base` (first axis slowest).
// Axes must have distinct keys (InputError otherwise); more than kMaxSweepConfigurations
// combinations or no axis at all is InputError.
std::vector<SweepConfiguration> expandGrid(const render::WorkloadConfig& base, const std::vector<SweepAxis>& axes);

// How a sweep makes each configuration's reference from the knobs' roles (ReferenceRole):
//   approximation knobs are set to their exact value (render.ssaa to `ssaa`, lighting.mode=all, ...)
//   and MSAA to `msaa` (clamped by the device and the render path);
//   look knobs are copied, except a varied one, which takes the sweep's base value (the scene's own
//   look, or the --set value);
//   content knobs are copied;
//   cost-only knobs are pinned to their registry value (render.path=forward, ...) or dropped.
struct ReferenceRules {
  const KnobRegistry* knobs = nullptr;  // the roles; null: every knob counts as content (tests)
  uint32_t ssaa = 4;                    // --reference-ssaa
  uint32_t msaa = 8;
  std::map<std::string, std::string> baseKnobs;  // the knobs before the grid's axes (--set, sweep file)
};

// True for a --vary key that is a --set knob; false for msaa, width, height and size.
bool isKnobAxis(const std::string& key);

// The role of an axis key under `rules`: msaa is an approximation, width/height/size content, a
// knob what the registry says (content without a registry). A knob the registry lacks is a
// programming error: every knob was checked against it before the sweep started.
ReferenceRole roleOf(const ReferenceRules& rules, const std::string& key);

// The reference of one configuration. Configurations that differ only in approximation and
// cost-only knobs, or in a varied look knob, share it.
render::WorkloadConfig referenceOf(const SweepConfiguration& configuration, const ReferenceRules& rules = {});

// The reference rendered one SSAA step down (render.ssaa = S - 1): its difference from the
// reference is the reference's convergence gap. None for a reference at SSAA 1.
std::optional<render::WorkloadConfig> convergenceStepOf(const render::WorkloadConfig& reference);

// The configuration's bias render: its reference with the configuration's varied cost-only knobs
// (e.g. render.path=visbuffer) at their values, with the highest MSAA the path allows. None when
// those knobs all hold the reference's pinned values. Its difference from the reference is the
// path's bias: what no amount of sampling removes.
std::optional<render::WorkloadConfig> biasRenderOf(const SweepConfiguration& configuration,
                                                   const render::WorkloadConfig& reference,
                                                   const ReferenceRules& rules = {});

// "render.path=visbuffer": the varied cost-only knobs of `configuration` that differ from the
// reference's pinned values ("" when none do).
std::string biasLabelOf(const SweepConfiguration& configuration, const ReferenceRules& rules = {});

// The varied keys (of the configurations' points) whose role is Look: a sweep varying one judges
// "change from the scene's look".
std::vector<std::string> variedLookKeys(const std::vector<SweepConfiguration>& configurations,
                                        const ReferenceRules& rules);

// A configuration whose error is within this factor of its reference's convergence gap cannot be
// told apart from the reference's own residual error: "unresolved".
inline constexpr double kUnresolvedGapFactor = 2.0;

struct SweepPlan {
  std::string scene;
  std::vector<SweepConfiguration> configurations;
  // Default: referenceOf(each configuration, referenceRules). Set to use one fixed configuration
  // instead (stress: the baseline rung; no convergence check or bias renders then).
  std::optional<render::WorkloadConfig> referenceOverride;
  ReferenceRules referenceRules;
  uint32_t warmup = 8;  // frames rendered before measuring
  // The compared images are of this frame (1-based) of every configuration and reference: animated
  // content (particles) depends on the frame number, and the reference renders only this many
  // frames (twice), which keeps a costly reference cheap.
  uint32_t imageFrame = 2;
  uint32_t frames = 64;                      // measured frames per configuration without untilStable
  std::optional<StabilityRule> untilStable;  // sample each until stable, at most stableFrameCap frames
  bool untilStableOnCpu = false;  // use cpuStabilityRule when the device is a CPU (lavapipe)
  StabilityRule cpuStabilityRule;
  uint32_t stableFrameCap = 128;
  uint32_t roundFrames = 16;  // frames per configuration per round
  uint32_t rewarmFrames = 1;  // dropped at the start of each round (others ran in between)
  // CPU devices (lavapipe), where one frame takes 0.1-10 s and nothing needs warming after the first
  // frame (no clocks ramp up; shaders and pipeline variants are compiled by the first frame): with
  // trimOnCpu no re-warm frame is dropped per visit, and in until-stable sweeps a visit checks the
  // stability rule every cpuStableCheckFrames frames and ends once the configuration is stable, so
  // no frame is rendered that the statistics do not need. With trimWarmupOnCpu as well (the CLI
  // without --warmup), warm-up ends with the compared frame (imageFrame).
  bool trimOnCpu = false;
  bool trimWarmupOnCpu = false;
  uint32_t cpuStableCheckFrames = 4;
  double maxMinutes = 0.0;    // 0: no limit; else measuring stops after this (after one full round)
  uint64_t seed = 1;          // order of the configurations within each round
  double alpha = 0.05;
  // A scene flown along a camera path (`fgbench sweep --path-times K`): each configuration is also
  // rendered alone at each of these path times (camera.time=T, frame imageFrame of a fresh
  // workload) and compared with its reference rendered at the same time; the front then judges
  // the mean of those errors (sweepError). Empty: a still scene, judged at frame imageFrame only.
  std::vector<double> pathTimes;
};

// Path times spread over a camera path of `durationS` seconds: the midpoints of K equal spans,
// (k + 1/2) x duration / K, rounded to the millisecond (each is a camera.time knob's text). K = 0,
// or a path without duration: none.
std::vector<double> spreadPathTimes(double durationS, uint32_t count);

// `config` seen still at path time `timeS` (the knob camera.time).
render::WorkloadConfig atPathTime(render::WorkloadConfig config, double timeS);

// Wall time of one render of a reference (ms): opening its workload, rendering its frames (up to
// the compared one) and reading the images back.
struct ReferenceRenderWall {
  double openMs = 0.0, framesMs = 0.0, readbackMs = 0.0;
};

// The error a sweep judges by: the LDR-FLIP mean of the display images (RMSE where FLIP was not
// computed).
inline double displayError(const ImageMetrics& display) {
  return display.flip ? display.flip->mean : display.rmse;
}

// A render compared with the reference: the convergence step, or a cost-only knob's bias render.
struct ReferenceCheck {
  std::string label;  // "render.ssaa=3", "render.path=visbuffer"
  render::WorkloadConfig workload;
  ImageMetrics display, hdr;  // against the reference: LDR-FLIP on the display image, HDR-FLIP on the HDR
  ReferenceRenderWall wall;
  [[nodiscard]] double gap() const { return displayError(display); }
};

struct ReferenceOutcome {
  render::WorkloadConfig workload;
  RenderedImages images;                  // first render
  ImageMetrics repeatDisplay, repeatHdr;  // second render against the first
  bool identical = false;                 // the two renders are bit-identical
  double renderMs = 0.0;                  // wall time of both renders and their comparison
  std::vector<ReferenceRenderWall> renders;  // each render's wall time, in order
  // The same reference one SSAA step down, against it: how converged the reference is.
  std::optional<ReferenceCheck> convergence;
  std::vector<ReferenceCheck> biases;  // converged renders of the varied cost-only knobs' values
  std::vector<RenderedImages> pathImages;  // at SweepPlan::pathTimes, one render each
  [[nodiscard]] double convergenceGap() const { return convergence ? convergence->gap() : 0.0; }
  // The index in `biases` of the render labelled `label` (none for "" or a label not rendered).
  [[nodiscard]] std::optional<std::size_t> biasIndex(const std::string& label) const;
};

// Wall time one configuration cost the sweep (ms): where a sweep's time goes, per configuration.
struct ConfigurationWall {
  double openMs = 0.0;     // opening its workload
  double warmupMs = 0.0;   // warm-up frames, including the compared frame and its readback
  double measureMs = 0.0;  // every measuring visit: re-warm frames, measured frames, waiting for the GPU
  double metricsMs = 0.0;  // its comparison with the reference
  uint32_t warmupFrames = 0, rewarmFrames = 0, visits = 0;
};

// A configuration's error at one path time, against its reference at that time.
struct PathTimeError {
  double timeS = 0.0;
  ImageMetrics display, hdr;
};

struct ConfigurationOutcome {
  SweepConfiguration configuration;
  std::size_t reference = 0;  // index into SweepResult::references
  RunResult run;              // measured frames (all rounds)
  MedianInterval frameGpu;    // median GPU frame time and its 95% interval
  bool stable = false;        // met the stability rule (until-stable sweeps)
  RenderedImages images;
  ImageMetrics display, hdr;  // against the reference: LDR-FLIP on the display image, HDR-FLIP on the HDR
  Image heatMap;              // LDR-FLIP map against the reference
  bool onFront = false;
  std::vector<std::size_t> dominatedBy;
  // Error within kUnresolvedGapFactor x its reference's convergence gap: it cannot be ranked by error.
  bool unresolved = false;
  std::optional<std::size_t> bias;  // index into its reference's biases (its cost-only knobs' bias)
  ConfigurationWall wall;
  std::vector<PathTimeError> pathErrors;  // one per SweepPlan::pathTimes (empty for a still scene)
  // Over pathErrors: the mean and the worst LDR-FLIP mean (0 when there are none), and where the
  // worst is.
  [[nodiscard]] double pathErrorMean() const;
  [[nodiscard]] double pathErrorWorst() const;
  [[nodiscard]] double pathErrorWorstTime() const;
};

// Wall time of the sweep by phase (ms), in the order they run: opening every configuration, the
// references, warming up, the measuring rounds, closing the devices, the metrics and the front,
// writing the outputs. totalMs is the sum of the phases before the report; the report phase is
// filled in by writeSweepOutputs.
struct SweepOverhead {
  double openMs = 0.0, referenceMs = 0.0, warmupMs = 0.0, measureMs = 0.0, closeMs = 0.0, metricsMs = 0.0,
         reportMs = 0.0, totalMs = 0.0;
};

// A shard of a sweep (`--shard K/N`): which configurations of the whole grid it measured.
struct ShardInfo {
  uint32_t index = 1, count = 1;         // K of N, 1-based
  std::size_t gridSize = 0;              // configurations in the whole grid
  std::vector<std::size_t> gridIndices;  // this shard's configurations' places in the grid, in order
};

struct SweepResult {
  std::string toolVersion;
  std::string scene;
  std::string sceneHash;
  render::DeviceDescription device;
  std::vector<SweepAxis> axes;
  ReferenceRules referenceRules;
  // Each varied key's reference role ("approximation", "look", "content", "cost-only").
  std::map<std::string, std::string> roles;
  // Varied look knobs: the error column is then the change from the scene's look, not only error.
  std::vector<std::string> lookKeys;
  std::vector<ReferenceOutcome> references;
  std::vector<ConfigurationOutcome> configurations;
  double errorFloor = 0.0;  // max LDR-FLIP mean between repeated reference renders
  double alpha = 0.05;
  uint64_t seed = 1;
  uint32_t rounds = 0;
  std::string stopReason;  // "frames" | "stable" | "time limit"
  std::optional<StabilityRule> untilStable;
  uint32_t frameCap = 0;
  uint32_t warmupFrames = 0;       // rendered before measuring, the compared frame among them
  uint32_t rewarmFrames = 0;       // dropped at the start of each visit
  uint32_t stableCheckFrames = 0;  // measured frames between stability checks (0: not until stable)
  SweepOverhead overhead;
  std::vector<double> pathTimes;   // SweepPlan::pathTimes: where each configuration was judged
  std::optional<ShardInfo> shard;  // set on a shard's result (its outputs then carry its images)
  std::size_t mergedShards = 0;    // sweep-merge: how many shards this result joins
};

struct SweepProgress {
  std::function<void(const std::string& phase)> phase;        // "reference 1/1", "measuring"
  std::function<void(uint32_t done, uint32_t total)> frames;  // measured frames so far / planned
};

// Runs the plan. InputError from opening a configuration (bad knob) surfaces before any reference
// is rendered.
SweepResult runSweep(const WorkloadOpener& open, const SweepPlan& plan, const SweepProgress& progress = {});

// Two configurations that render the same (they share a reference).
bool sameWorkload(const render::WorkloadConfig& a, const render::WorkloadConfig& b);

// `--shard K/N` (1 <= K <= N <= 64); InputError naming the option otherwise.
struct ShardSpec {
  uint32_t index = 1, count = 1;
};
ShardSpec parseShard(const std::string& text);

// The grid indices shard `spec` measures. Shards are cut along reference groups (configurations
// sharing a reference stay in one shard, so no reference is rendered twice: the reference is a
// sweep's costliest render), each group to the shard with the fewest configurations so far, in the
// grid's order. InputError when the grid has fewer groups than shards.
std::vector<std::size_t> shardConfigurations(const std::vector<SweepConfiguration>& grid, const ReferenceRules& rules,
                                             ShardSpec spec);

// sweep.json's schema version (docs/sweep.md): writeSweepOutputs writes it, mergeSweepShards checks it.
inline constexpr int kSweepSchema = 1;

// `fgbench sweep-merge`: the shards' sweep.json (and images/) joined into one result, the
// configurations back in grid order and the front marked over all of them. InputError (exit 2)
// naming the directory when a shard is missing, given twice, or of another scene, build, device
// model or grid.
SweepResult mergeSweepShards(const std::vector<std::filesystem::path>& directories);

// Renders `config` twice, each in a freshly opened workload, up to frame `frames`: the reference
// images (the first render) and its noise floor (the second against the first). A step of runSweep,
// exposed for the overhead benchmark.
ReferenceOutcome renderReference(const WorkloadOpener& open, const render::WorkloadConfig& config, uint32_t frames);

// Renders the reference's convergence step and the bias renders its configurations need.
// `say` hears each render before it starts ("convergence (render.ssaa=3)", "bias of render.path=visbuffer").
void checkReference(const WorkloadOpener& open, ReferenceOutcome& reference, const SweepPlan& plan,
                    const std::vector<const SweepConfiguration*>& configurations, uint32_t frames,
                    const std::function<void(const std::string&)>& say = {});

// Compares every configuration with its reference, marks the unresolved ones and the front
// (runSweep's last step; exposed for the overhead benchmark and tests).
void compareWithReferences(SweepResult& result);
// Marks each configuration on or off the front of its view: configurations that differ in a varied
// content axis (camera.distance, the size, a scene's geometry) render different images, each
// judged against its own reference, so one never dominates another; each view has its own front.
void markFront(SweepResult& result);
// The varied axes whose role is content, in axis order: what tells the views apart.
std::vector<std::string> viewKeys(const SweepResult& result);
// The configuration's view: its values of viewKeys ("camera.distance=4"; "" when no content varies).
std::string viewOf(const SweepResult& result, const ConfigurationOutcome& configuration);

// Renders each configuration and each reference at every path time of `plan` and fills the
// configurations' pathErrors (runSweep's step before compareWithReferences; nothing without path
// times).
void judgeAlongPath(const WorkloadOpener& open, const SweepPlan& plan, SweepResult& result,
                    const std::function<void(const std::string&)>& say = {});

// The error the front is built on: LDR-FLIP mean against the reference (RMSE without FLIP); along a
// camera path, the mean of that error over the path times.
double sweepError(const ConfigurationOutcome& c);

}  // namespace fgb::harness
