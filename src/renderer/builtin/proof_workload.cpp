// ProofWorkload: the proof scene on a Vulkan device — compile once, execute every frame (timings
// through GraphFrameTimer, as the scene workload), images read back from the last frame.
#include "proof_workload.hpp"

#include <fgb/core/error.hpp>
#include <fgb/graph/critical_path.hpp>
#include <fgb/graph/dot.hpp>
#include <fgb/renderer/describe_device.hpp>
#include <fgb/renderer/frame_timer.hpp>
#include <fgb/vulkan/backend.hpp>

#include "pixels.hpp"

namespace fgb::render {
namespace {

class ProofWorkload final : public Workload {
 public:
  explicit ProofWorkload(const WorkloadConfig& config) {
    device_ = vulkan::createDevice({.selector = config.device, .validation = config.validation});
    description_ = describeDevice(device_->adapter());
    settings_ = proofSettings(config, device_->sampleCounts());
    rhi::checkRenderSize(device_->adapter(), settings_.width, settings_.height);
    resources_ = createProofResources(*device_, settings_);
    graph_ = device_->compile(buildProofGraph(settings_, resources_),
                              {.name = "builtin:proof", .queues = settings_.queues, .separateQueues = settings_.separateQueues});
  }

  ~ProofWorkload() override {
    // Destroy order: the graph waits for its work before the device goes.
    graph_.reset();
  }

  const DeviceDescription& device() const override { return description_; }

  FrameTiming renderFrame() override { return timer_.execute(*device_, *graph_); }
  std::vector<FrameTiming> finish() override { return timer_.finish(*device_, *graph_); }
  FrameTiming renderIsolatedFrame() override { return timer_.executeIsolated(*device_, *graph_); }
  std::vector<double> criticalPathShares(const std::vector<double>& costMs) const override {
    return graph::criticalPath(graph::schedulePredecessors(graph_->compiled()), costMs).shareOfPath;
  }

  ImageRGBA32F readHdr() override {
    device_->waitIdle();
    return fromRgba16f(device_->mapped(resources_.hdrReadback), settings_.width, settings_.height);
  }

  ImageRGBA32F readDisplay() override {
    device_->waitIdle();
    return fromRgba8Srgb(device_->mapped(resources_.displayReadback), settings_.width, settings_.height);
  }

  std::string graphviz(GraphDetail detail) const override {
    return graph::toDot(graph_->declaration(), graph_->compiled(),
                        detail == GraphDetail::Full ? graph::DotDetail::Full : graph::DotDetail::Brief);
  }

  std::map<std::string, double> stats() const override {
    const auto& compiled = graph_->compiled();
    return {{"instances", 1},
            {"instances_visible", 1},
            {"triangles", settings_.triangles},
            {"triangles_visible", settings_.triangles},
            {"lights", 0},
            {"nodes", static_cast<double>(graph_->declaration().nodes().size())},
            {"nodes_alive", static_cast<double>(compiled.order.size())},
            {"transient_bytes_aliased", static_cast<double>(compiled.aliasing.peakBytesAliased)},
            {"transient_bytes_unaliased", static_cast<double>(compiled.aliasing.peakBytesUnaliased)}};
  }

  uint64_t validationMessages() const override { return device_->validationMessages(); }

 private:
  std::unique_ptr<rhi::Device> device_;
  DeviceDescription description_;
  ProofSettings settings_;
  ProofResources resources_;
  std::unique_ptr<rhi::ExecutableGraph> graph_;
  GraphFrameTimer timer_;
};

}  // namespace

std::unique_ptr<Workload> openProofWorkload(const WorkloadConfig& config) { return std::make_unique<ProofWorkload>(config); }

}  // namespace fgb::render
