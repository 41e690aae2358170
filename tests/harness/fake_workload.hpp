// A scripted Workload for testing the harness without Vulkan: pass times encode the frame number
// so tests can tell which frames were kept; timings can be delivered late, as a real GPU does.
#pragma once

#include <fgb/renderer/workload.hpp>

#include <deque>

namespace fgb::harness::testing {

class FakeWorkload : public render::Workload {
 public:
  // latency: how many frames late the timings arrive (0 = immediately).
  explicit FakeWorkload(std::size_t latency = 0, bool hostTimestamps = true) : latency_(latency) {
    device_.name = "llvmpipe (fake)";
    device_.type = "cpu";
    device_.driver = "fake 1.0";
    device_.hostTimestamps = hostTimestamps;
  }

  const render::DeviceDescription& device() const override { return device_; }

  render::FrameTiming renderFrame() override {
    const double f = constantTimes_ ? 0.0 : static_cast<double>(rendered_);
    ++rendered_;
    render::FrameTiming t;
    t.passes.push_back({"Cull", "compute", false, 0.1 + f, 0.0});
    t.passes.push_back({"Draw <main>", "graphics", false, 1.0 + f, 0.1 + f});
    t.passes.push_back({"Debug", "graphics", true, 0.0, -1.0});
    t.gpuFrameMs = 1.1 + 2 * f;
    t.cpuFrameMs = 2.0 + f;
    t.submitMs = 0.5;
    t.nodesRecorded = rendered_ <= 2 ? 3 : 1;  // every node in the first two frames, then one
    t.nodesReused = 3 - t.nodesRecorded;
    if (pathStep_ > 0.0) {
      t.pathTimeS = pathStep_ * static_cast<double>(rendered_ - 1);
      // Along the path, frame 2 (counting warm-up) is the slowest and frame 4 the next.
      if (rendered_ - 1 == 2) t.gpuFrameMs = 100.0;
      if (rendered_ - 1 == 4) t.gpuFrameMs = 50.0;
    }
    pending_.push_back(t);
    if (pending_.size() <= latency_) return {};
    render::FrameTiming ready = pending_.front();
    pending_.pop_front();
    return ready;
  }

  std::vector<render::FrameTiming> finish() override {
    std::vector<render::FrameTiming> rest(pending_.begin(), pending_.end());
    pending_.clear();
    if (dropOnFinish_ && !rest.empty()) rest.pop_back();
    return rest;
  }

  render::ImageRGBA32F readHdr() override { return image(2.0f); }
  render::ImageRGBA32F readDisplay() override { return image(0.5f); }
  std::string graphviz(render::GraphDetail detail) const override {
    return detail == render::GraphDetail::Brief ? "digraph brief {}" : "digraph full {}";
  }
  std::map<std::string, double> stats() const override { return {{"instances", 3}, {"triangles", 36}}; }
  uint64_t validationMessages() const override { return 0; }
  std::vector<render::NonFiniteCounts> nonFiniteCounts() const override { return nonFinite_; }
  void setNonFiniteCounts(std::vector<render::NonFiniteCounts> counts) { nonFinite_ = std::move(counts); }

  void dropOneTimingOnFinish() { dropOnFinish_ = true; }
  // Frames fly a camera path, frame e (warm-up included) at e * step seconds.
  void flyPath(double step) { pathStep_ = step; }
  // Every frame takes the same time (frame 0's), so a median's interval is as narrow as can be.
  void constantTimes() { constantTimes_ = true; }
  std::size_t rendered() const { return rendered_; }
  double pathStep_ = 0.0;

 private:
  static render::ImageRGBA32F image(float v) {
    render::ImageRGBA32F img;
    img.width = 8;
    img.height = 4;
    img.pixels.assign(8 * 4 * 4, v);
    return img;
  }

  render::DeviceDescription device_;
  std::size_t latency_;
  std::size_t rendered_ = 0;
  bool dropOnFinish_ = false;
  bool constantTimes_ = false;
  std::deque<render::FrameTiming> pending_;
  std::vector<render::NonFiniteCounts> nonFinite_;
};

}  // namespace fgb::harness::testing
