// SceneWorkload: a scene file rendered by the render features through one compiled frame graph.
#include <algorithm>
#include <array>
#include <cstring>
#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/graph/critical_path.hpp>
#include <fgb/graph/data_inputs.hpp>
#include <fgb/graph/dot.hpp>
#include <fgb/renderer/describe_device.hpp>
#include <fgb/renderer/frame_timer.hpp>
#include <fgb/renderer/scene_workload.hpp>
#include <fgb/scene/cache.hpp>
#include <fgb/scene/load.hpp>
#include <fgb/scene/stats.hpp>
#include <fgb/vulkan/backend.hpp>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>

#include "../features/context/render_feature.hpp"
#include "../features/exposure/exposure_feature.hpp"
#include "../features/finite_check/finite_check_feature.hpp"
#include "../features/pass_capture/pass_capture_feature.hpp"
#include "frame_update.hpp"
#include "gpu_upload.hpp"
#include "image_readback.hpp"
#include "render_paths.hpp"

namespace fgb::render {
namespace {

using features::FrameTargets;

// The frame graph leaves the HDR image sampled by tone mapping and the display image as a target.
constexpr graph::ImportState kHdrFinal{graph::kStageFragmentShader, graph::kAccessShaderSampledRead,
                                       graph::Layout::ShaderReadOnly, graph::QueueClass::Graphics};
constexpr graph::ImportState kDisplayFinal{graph::kStageColorAttachmentOutput, graph::kAccessColorAttachmentWrite,
                                           graph::Layout::ColorAttachment, graph::QueueClass::Graphics};
// With compute post passes (render_paths.hpp): tone mapping samples the HDR image and writes the
// display image as storage, in compute; leaving them there spares a transition every frame.
constexpr graph::ImportState kHdrFinalCompute{graph::kStageComputeShader, graph::kAccessShaderSampledRead,
                                              graph::Layout::ShaderReadOnly, graph::QueueClass::Graphics};
constexpr graph::ImportState kDisplayFinalCompute{graph::kStageComputeShader, graph::kAccessShaderStorageWrite,
                                                  graph::Layout::General, graph::QueueClass::Graphics};
constexpr graph::ImportState kDiscard{graph::kStageNone, graph::kAccessNone, graph::Layout::Undefined,
                                      graph::QueueClass::Graphics};

constexpr graph::ImportState kExposureState{
    graph::kStageVertexShader | graph::kStageFragmentShader | graph::kStageComputeShader,
    graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite, graph::Layout::Undefined,
    graph::QueueClass::Graphics};

// The HDR clear: the background radiance, scaled with the lights and pre-exposed. With auto
// exposure it is pre-exposed with the starting exposure, so the backdrop keeps a fixed display
// value; its alpha of 0 keeps it out of the exposure measurement (geometry writes alpha > 0).
std::array<float, 4> backgroundClear(const scene::PostSettings& post) {
  const float scale = post.lightScale * initialExposure(post).preExposure;
  const auto& b = features::kBackgroundRadiance;
  const auto channel = [&](float radiance) { return std::min(radiance * scale, 65504.0f); };  // R16F max
  return {channel(b[0]), channel(b[1]), channel(b[2]), 0.0f};
}

// render.ssaa multiplies the size the scene passes render at: it must fit the device's images too.
void checkSupersampledSize(const rhi::AdapterInfo& adapter, const features::RenderSettings& settings) {
  const uint32_t limit = adapter.maxImageDimension2D;
  if (settings.ssaa == 1 || limit == 0 || std::max(settings.sceneWidth(), settings.sceneHeight()) <= limit) return;
  throw InputError("--set render.ssaa=" + std::to_string(settings.ssaa) + ": the scene passes' " +
                   std::to_string(settings.sceneWidth()) + "x" + std::to_string(settings.sceneHeight()) +
                   " is larger than the largest image " + adapter.name + " supports, " + std::to_string(limit) + "x" +
                   std::to_string(limit));
}

uint32_t jsonCount(const nlohmann::json& section, const char* key, uint32_t fallback) {
  if (!section.is_object() || !section.contains(key) || !section[key].is_number_unsigned()) return fallback;
  return section[key].get<uint32_t>();
}

// --time-step, else the scene file's render.time_step, else 1/60 s (the particles' step before
// camera paths existed: a still scene's frames are what they were).
double timeStepOf(const WorkloadConfig& config, const scene::SceneDescription& description) {
  if (config.timeStep > 0.0) return config.timeStep;
  const nlohmann::json& renderer = description.renderer;
  if (renderer.is_object() && renderer.contains("render") && renderer["render"].contains("time_step")) {
    const nlohmann::json& step = renderer["render"]["time_step"];
    if (!step.is_number() || !(step.get<double>() > 0.0) || !(step.get<double>() <= 60.0))
      throw InputError(description.path.string() + ": field 'render.time_step': expected seconds in (0, 60]");
    return step.get<double>();
  }
  return 1.0 / 60.0;
}

features::RenderSettings makeSettings(const WorkloadConfig& config, const scene::SceneDescription& description,
                                      uint32_t sampleCounts, const features::RenderPath& path) {
  const nlohmann::json render = description.renderer.is_object() && description.renderer.contains("render")
                                    ? description.renderer["render"]
                                    : nlohmann::json();
  features::RenderSettings settings;
  settings.width = config.width ? config.width : jsonCount(render, "width", 640);
  settings.height = config.height ? config.height : jsonCount(render, "height", 360);
  uint32_t msaa = config.msaa ? config.msaa : jsonCount(render, "msaa", 1);
  if (msaa != 1 && msaa != 2 && msaa != 4 && msaa != 8)
    throw InputError("--msaa " + std::to_string(msaa) + ": expected 1|2|4|8");
  const uint32_t requestedMsaa = msaa;
  // Clamped to the nearest supported count not above the request (lavapipe: {1, 4}).
  if (const uint32_t supported = rhi::clampSampleCount(msaa, sampleCounts); supported != msaa) {
    std::cerr << "warning: --msaa " << msaa << " clamped to " << supported << " (not supported by the device)\n";
    msaa = supported;
  }
  settings.msaa = msaa;
  features::applyRendererKnobs(settings, config.knobs);
  settings.checkFinite = config.checkFinite;
  settings.capture = config.capture;
  if (config.clampMsaaToPath) settings.msaa = std::min(settings.msaa, path.maxMsaa);
  checkRenderPathSettings(path, config.clampMsaaToPath ? settings.msaa : requestedMsaa, settings.debugView);
  return settings;
}

// The visibility words (uint64 per pixel: reversed-Z depth key << 32 | draw << 7 | triangle, 0 where
// nothing was drawn) in a form that compares across runs: depth, draw index and triangle as floats.
// The draw index is the cluster's ClusterDraw index, not its slot in the visible list, so it does not
// depend on the order of the culling appends.
ImageRGBA32F decodeVisibilityWords(graph::Extent extent, const std::vector<std::byte>& bytes) {
  ImageRGBA32F image{extent.width, extent.height, std::vector<float>(size_t{extent.width} * extent.height * 4, 0.0f)};
  for (size_t i = 0; i < size_t{extent.width} * extent.height; ++i) {
    uint64_t word = 0;
    std::memcpy(&word, bytes.data() + 8 * i, 8);
    if (word == 0) continue;
    const auto key = uint32_t(word >> 32);
    float depth = 0.0f;
    std::memcpy(&depth, &key, 4);
    image.pixels[i * 4] = depth;
    image.pixels[i * 4 + 1] = float(uint32_t(word) >> 7);
    image.pixels[i * 4 + 2] = float(uint32_t(word) & 0x7fu);
    image.pixels[i * 4 + 3] = 1.0f;
  }
  return image;
}

class SceneWorkload final : public Workload {
 public:
  explicit SceneWorkload(const WorkloadConfig& config) {
    Stopwatch timer;
    // First: a bad render path file is bad input before any work.
    path_ = renderPathOf(config.knobs);
    scene::LoadOptions loadOptions;
    const std::filesystem::path cacheDir =
        config.cacheDir.empty() ? scene::CookedCache::defaultDirectory() : std::filesystem::path(config.cacheDir);
    loadOptions.cacheDir = cacheDir;
    loadOptions.knobs = config.knobs;  // the scene's own keys are parsed once, there
    loaded_ = scene::loadScene(config.scenePath, loadOptions);
    startup_.sceneMs = timer.lap();

    rhi::DeviceOptions deviceOptions;
    deviceOptions.selector = config.device;
    deviceOptions.validation = config.validation;
    deviceOptions.pipelineCacheDir = (cacheDir / "pipelines").string();
    deviceOptions.framesInFlight = features::kFramesInFlight;  // the per-frame buffers' copies
    device_ = vulkan::createDevice(deviceOptions);
    description_ = describeDevice(device_->adapter());
    settings_ = makeSettings(config, loaded_.description, device_->sampleCounts(), path_);
    rhi::checkRenderSize(device_->adapter(), settings_.width, settings_.height);
    checkSupersampledSize(device_->adapter(), settings_);
    resolveDeviceSettings(settings_, path_, *device_);
    startup_.deviceMs = timer.lap();

    gpu_ = uploadScene(*device_, loaded_.scene, settings_, path_);
    startup_.uploadMs = timer.lap();
    frameUpdate_ = std::make_unique<FrameUpdate>(*device_, gpu_, loaded_.scene, settings_,
                                                 FrameClock::of(loaded_.scene, timeStepOf(config, loaded_.description)));
    createFeatures(config.captureNodes);
    buildFrameGraph();
    checkCaptureNodes(config.captureNodes);
    startup_.graphMs = timer.lap();
    simulateToStillTime();
    const rhi::PipelineStats pipelines = device_->pipelineStats();
    startup_.pipelinesMs = pipelines.creationMs;
    startup_.pipelines = pipelines.created;
    startup_.pipelineCache = pipelines.cache;
  }

  const DeviceDescription& device() const override { return description_; }

  FrameTiming renderFrame() override { return runFrame(rhi::RunMode::Sequential); }
  std::vector<FrameTiming> finish() override { return timer_.finish(*device_, *graph_); }
  FrameTiming renderIsolatedFrame() override { return runFrame(rhi::RunMode::Isolated); }
  std::vector<double> criticalPathShares(const std::vector<double>& costMs) const override {
    return graph::criticalPath(graph::schedulePredecessors(graph_->compiled()), costMs).shareOfPath;
  }

  bool drawsClusters() const override { return path_.uploadClusters; }
  uint32_t queuesUsed() const override {
    std::set<uint32_t> queues;
    for (const auto& submit : graph_->compiled().submits) queues.insert(submit.queue);
    return uint32_t(queues.size());
  }
  bool setAsyncCompute(bool on) override {
    if (settings_.asyncCompute == on) return true;
    (void)timer_.finish(*device_, *graph_);  // nothing of the old graph may still be in flight
    device_->waitIdle();
    settings_.asyncCompute = on;
    graph_.reset();
    const double compileMs = startup_.graphCompileMs;  // start-up figures describe the first compile
    buildFrameGraph();
    startup_.graphCompileMs = compileMs;
    return true;
  }

  ImageRGBA32F readHdr() override { return hdrReadback_->read(); }
  ImageRGBA32F readDisplay() override { return displayReadback_->read(); }

  std::string graphviz(GraphDetail detail) const override {
    return graph::toDot(graph_->declaration(), graph_->compiled(),
                        detail == GraphDetail::Brief ? graph::DotDetail::Brief : graph::DotDetail::Full);
  }

  std::map<std::string, double> stats() const override {
    const auto sceneStats = scene::stats(loaded_.scene, float(settings_.width) / float(settings_.height));
    std::map<std::string, double> result{{"instances", sceneStats.instances},
                                         {"triangles", double(sceneStats.triangles)},
                                         {"lights", sceneStats.lights},
                                         {"emitters", sceneStats.emitters},
                                         {"materials", sceneStats.materials}};
    for (const auto& feature : features_) feature->addStats(result);
    return result;
  }

  uint64_t validationMessages() const override { return device_->validationMessages(); }

  std::vector<NonFiniteCounts> nonFiniteCounts() const override {
    auto counts = finiteCheck_->counts();
    // Execution order: the first pass with a bad value is where it was born.
    const auto& order = graph_->compiled().order;
    std::vector<size_t> position(graph_->declaration().nodes().size(), order.size());
    for (size_t i = 0; i < order.size(); ++i) position[order[i]] = i;
    std::stable_sort(counts.begin(), counts.end(),
                     [&](const auto& a, const auto& b) { return position[a.node] < position[b.node]; });
    std::vector<NonFiniteCounts> result;
    for (const auto& c : counts) result.push_back({c.pass, c.nan, c.inf, c.overHalfMax});
    return result;
  }
  StartupTimes startup() const override { return startup_; }

  std::vector<PassCapture> capturedPasses() override {
    device_->waitIdle();
    std::vector<PassCapture> result;
    for (const features::CapturedBytes& captured : passCapture_->read()) {
      PassCapture capture{captured.pass, captured.resource, CaptureContent::Color, {}};
      if (captured.content == features::CapturedContent::Visibility) {
        capture.content = CaptureContent::Visibility;
        capture.image = decodeVisibilityWords(captured.extent, captured.bytes);
      } else {
        capture.content =
            captured.content == features::CapturedContent::Depth ? CaptureContent::Depth : CaptureContent::Color;
        // The opaque-depth buffer holds one float per pixel, as an R32Sfloat texture would.
        const graph::Format format =
            captured.format == graph::Format::Undefined ? graph::Format::R32Sfloat : captured.format;
        capture.image = decodeTexels(format, captured.extent, captured.bytes);
      }
      result.push_back(std::move(capture));
    }
    return result;
  }

  std::vector<PassNode> passGraph() const override {
    const graph::FrameGraph& declaration = graph_->declaration();
    const auto inputs = graph::dataInputs(declaration);
    std::vector<PassNode> nodes;
    for (size_t node = 0; node < inputs.size(); ++node) {
      const std::string& name = declaration.nodes()[node].name;
      // The inspecting nodes (--check-finite, --capture) are declared last: the frame's end.
      if (name.rfind("Finite Check", 0) == 0 || name.rfind("Capture: ", 0) == 0) break;
      nodes.push_back({name, inputs[node]});
    }
    return nodes;
  }

  [[nodiscard]] const graph::FrameGraph& declaration() const { return graph_->declaration(); }

 private:
  // A frame: its per-frame values written into the copy it owns, then executed (Isolated: each
  // pass alone on an idle device, the calibration).
  FrameTiming runFrame(rhi::RunMode mode) {
    const uint64_t execution = graph_->executions();
    // The copy this frame writes was last read kFramesInFlight frames ago: wait for that one (the
    // executor would wait for it anyway; that is throttling, not the frame's CPU time).
    if (const auto& reader = readers_[execution % features::kFramesInFlight]) device_->wait(*reader);
    Stopwatch update;
    frameUpdate_->write(execution);
    const double updateMs = update.lap();
    const FrameClock& clock = frameUpdate_->clock();
    const double pathTimeS = clock.flies ? clock.pathTime(execution) : -1.0;
    FrameTiming timing = mode == rhi::RunMode::Isolated
                             ? timer_.executeIsolated(*device_, *graph_, updateMs, pathTimeS)
                             : timer_.execute(*device_, *graph_, updateMs, pathTimeS);
    readers_[execution % features::kFramesInFlight] = timer_.lastTicket();
    return timing;
  }

  // camera.time=T: the executions that simulate the particles up to T, all but the last, run now
  // (not measured), so the first measured frame shows the particles at T, as the path does.
  void simulateToStillTime() {
    const auto& steps = frameUpdate_->clock().stillSteps;
    if (!steps) return;
    while (graph_->executions() + 1 < *steps) renderFrame();
    (void)timer_.finish(*device_, *graph_);  // their timings are dropped
  }

  // --capture NAME,...: every name must be a node of this frame (exit 2 listing them).
  void checkCaptureNodes(const std::vector<std::string>& wanted) const {
    const auto& nodes = graph_->declaration().nodes();
    for (const std::string& name : wanted) {
      if (std::any_of(nodes.begin(), nodes.end(), [&](const auto& node) { return node.name == name; })) continue;
      std::string known;
      for (const auto& node : nodes) {
        if (node.name.rfind("Capture: ", 0) == 0 || node.name.rfind("Finite Check", 0) == 0) continue;
        known += (known.empty() ? "" : ", ") + node.name;
      }
      throw InputError("--capture: no node '" + name + "' in this frame; its nodes: " + known);
    }
  }

  void createFeatures(const std::vector<std::string>& captureNodes) {
    RenderPathPlan plan = planRenderPath(path_);
    features_ = std::move(plan.features);
    hdrStorage_ = plan.computeWritesHdr;
    displayStorage_ = plan.computeWritesDisplay;
    displayFormat_ = plan.displayFormat;
    // Last: it inspects every node declared before it (see finite_check_feature.hpp).
    auto finiteCheck = std::make_unique<features::FiniteCheckFeature>();
    finiteCheck_ = finiteCheck.get();
    features_.push_back(std::move(finiteCheck));
    // After the finite check, whose nodes it skips: it copies what the frame's own nodes wrote.
    auto passCapture = std::make_unique<features::PassCaptureFeature>(captureNodes);
    passCapture_ = passCapture.get();
    features_.push_back(std::move(passCapture));
    features::FeatureInit init{*device_, gpu_, settings_, path_};
    for (auto& feature : features_) feature->initialize(init);
  }

  // Where the frame leaves the imported images (tone mapping is their last user).
  graph::ImportState hdrFinal() const { return displayStorage_ ? kHdrFinalCompute : kHdrFinal; }
  graph::ImportState displayFinal() const { return displayStorage_ ? kDisplayFinalCompute : kDisplayFinal; }

  FrameTargets makeTargets(graph::FrameGraph& graph) {
    const graph::Extent extent{settings_.width, settings_.height, 1};
    const rhi::TextureUsage storage = hdrStorage_ ? rhi::kTextureStorage : rhi::TextureUsage{0};
    hdrTexture_ = device_->createTexture({"hdr", features::kHdrFormat, extent, 1, 1, 1,
                                          rhi::kTextureColorAttachment | rhi::kTextureSampled |
                                              rhi::kTextureTransferSrc | storage});
    const rhi::TextureUsage displayStorage = displayStorage_ ? rhi::kTextureStorage : rhi::TextureUsage{0};
    displayTexture_ = device_->createTexture({"display", displayFormat_, extent, 1, 1, 1,
                                              rhi::kTextureColorAttachment | rhi::kTextureTransferSrc | displayStorage});
    FrameTargets targets;
    targets.outputExtent = extent;
    targets.extent = {settings_.sceneWidth(), settings_.sceneHeight(), 1};
    targets.samples = settings_.msaa;
    targets.background = backgroundClear(loaded_.scene.post);
    if (loaded_.scene.post.autoExposure) {
      // Written by the "Exposure" node, read by the next frame's colour passes: the state carries
      // over between frames, all on the graphics queue.
      targets.exposure = graph.importBuffer("exposure", {sizeof(gpu::Exposure), {}}, rhi::external(gpu_.exposure),
                                            kExposureState, kExposureState);
    }
    const graph::TextureHandle hdr = graph.importTexture("hdr", {features::kHdrFormat, extent, 1, 1, 1, {}, 0},
                                                         rhi::external(hdrTexture_), kDiscard, hdrFinal());
    if (settings_.ssaa == 1) {
      targets.hdr = hdr;
    } else {
      targets.outputHdr = hdr;
      targets.hdr = graph.createTexture("hdr ssaa", {features::kHdrFormat, targets.extent, 1, 1, 1, {}, 0});
    }
    targets.display = graph.importTexture("display", {displayFormat_, extent, 1, 1, 1, {}, 0},
                                          rhi::external(displayTexture_), kDiscard, displayFinal());
    targets.color = settings_.msaa == 1
                        ? targets.hdr
                        : graph.createTexture("hdr msaa", {features::kHdrFormat, {}, 1, 1, settings_.msaa, targets.hdr, 0});
    targets.depth = graph.createTexture("depth", {features::kDepthFormat, {}, 1, 1, settings_.msaa, targets.hdr, 0});
    return targets;
  }

  void buildFrameGraph() {
    graph::FrameGraph graph;
    features::Blackboard board;
    const auto& targets = board.set(makeTargets(graph));
    for (auto& feature : features_)
      if (feature->enabled()) feature->declare(graph, board);
    rhi::GraphOptions options;
    options.name = "frame";
    if (!settings_.asyncCompute) options.queues = 1;
    options.recordEveryFrame = settings_.recordEveryFrame;
    options.nodeBuffers = settings_.nodeBuffers;
    if (!settings_.slowPass.empty()) {
      std::vector<std::string> passes;
      for (const auto& node : graph.nodes()) passes.push_back(node.name);
      const features::SlowPass slow = features::slowPassOf(settings_.slowPass, passes);
      options.slowNode = slow.pass;
      options.slowFraction = slow.fraction;
    }
    graph::CompileProfile profile;
    options.compileProfile = &profile;
    graph_ = device_->compile(std::move(graph), options);
    for (const double us : profile.microseconds) startup_.graphCompileMs += us / 1000.0;
    const graph::Extent extent = targets.outputExtent;
    hdrReadback_ = std::make_unique<ImageReadback>(*device_, hdrTexture_, features::kHdrFormat, extent, hdrFinal());
    displayReadback_ =
        std::make_unique<ImageReadback>(*device_, displayTexture_, displayFormat_, extent, displayFinal());
  }

  scene::LoadedScene loaded_;
  std::unique_ptr<rhi::Device> device_;
  DeviceDescription description_;
  StartupTimes startup_;
  features::RenderSettings settings_;
  features::RenderPath path_;  // render.path
  features::GpuScene gpu_;
  std::vector<std::unique_ptr<features::IRenderFeature>> features_;
  features::FiniteCheckFeature* finiteCheck_ = nullptr;  // owned by features_
  features::PassCaptureFeature* passCapture_ = nullptr;  // owned by features_
  bool hdrStorage_ = false;  // a compute node writes the HDR target
  bool displayStorage_ = false;  // a compute node writes the display image
  graph::Format displayFormat_ = features::kDisplayFormat;  // holds sRGB-encoded bytes in either format
  rhi::TextureId hdrTexture_;
  rhi::TextureId displayTexture_;
  std::unique_ptr<FrameUpdate> frameUpdate_;
  std::array<std::optional<rhi::RunTicket>, features::kFramesInFlight> readers_;  // the last execution per copy
  std::unique_ptr<rhi::ExecutableGraph> graph_;
  std::unique_ptr<ImageReadback> hdrReadback_;
  std::unique_ptr<ImageReadback> displayReadback_;
  GraphFrameTimer timer_;
};

}  // namespace

std::unique_ptr<Workload> openSceneWorkload(const WorkloadConfig& config) {
  return std::make_unique<SceneWorkload>(config);
}

const graph::FrameGraph* frameGraphOf(const Workload& workload) {
  const auto* scene = dynamic_cast<const SceneWorkload*>(&workload);
  return scene ? &scene->declaration() : nullptr;
}

}  // namespace fgb::render
