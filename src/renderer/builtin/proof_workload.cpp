// ProofWorkload: the proof scene on a Vulkan device — compile once, execute every frame, timings of
// frame N collected while frame N+1 is recorded, images read back from the last frame.
#include "proof_workload.hpp"

#include "pixels.hpp"

#include <fgb/core/error.hpp>
#include <fgb/renderer/describe_device.hpp>
#include <fgb/graph/dot.hpp>
#include <fgb/vulkan/backend.hpp>

#include <deque>
#include <unordered_map>

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

  FrameTiming renderFrame() override {
    const rhi::RunTicket ticket = device_->execute(*graph_);
    cpuMs_[ticket.execution] = graph_->lastHostTimes().recordMs;
    collect();
    if (ready_.empty()) return {};
    FrameTiming oldest = std::move(ready_.front());
    ready_.pop_front();
    return oldest;
  }

  std::vector<FrameTiming> finish() override {
    device_->waitIdle();
    collect();
    std::vector<FrameTiming> rest(std::make_move_iterator(ready_.begin()), std::make_move_iterator(ready_.end()));
    ready_.clear();
    return rest;
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
  void collect() {
    for (auto& t : graph_->takeTimings()) ready_.push_back(toFrameTiming(t));
  }

  FrameTiming toFrameTiming(const rhi::GraphTimings& t) {
    const auto& nodes = graph_->declaration().nodes();
    const auto& info = graph_->compiled().nodes;
    FrameTiming frame;
    for (uint32_t n = 0; n < nodes.size(); ++n) {
      PassTiming pass;
      pass.name = nodes[n].name;
      pass.queue = std::string(graph::toString(nodes[n].queue));
      pass.culled = info[n].culled;
      pass.gpuMs = t.nodeMs[n];
      pass.gpuStartMs = t.nodeStartMs[n];
      frame.passes.push_back(std::move(pass));
    }
    frame.gpuFrameMs = t.gpuMs;
    if (const auto it = cpuMs_.find(t.execution); it != cpuMs_.end()) {
      frame.cpuFrameMs = it->second;
      cpuMs_.erase(it);
    }
    return frame;
  }

  std::unique_ptr<rhi::Device> device_;
  DeviceDescription description_;
  ProofSettings settings_;
  ProofResources resources_;
  std::unique_ptr<rhi::ExecutableGraph> graph_;
  std::deque<FrameTiming> ready_;
  std::unordered_map<uint64_t, double> cpuMs_;
};

}  // namespace

std::unique_ptr<Workload> openProofWorkload(const WorkloadConfig& config) { return std::make_unique<ProofWorkload>(config); }

}  // namespace fgb::render
