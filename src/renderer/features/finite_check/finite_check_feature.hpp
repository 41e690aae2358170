// --check-finite: after every pass that writes a float colour texture, a small compute node
// ("Finite Check: <pass>") counts the pixels holding a NaN, an Inf or a finite magnitude above half
// of R16F's maximum (32752), over every texture that pass wrote (every sample of an MSAA one).
// It is declared last and reads the exact versions each pass produced, so the graph orders every
// check right after its pass (and before whatever overwrites the texture). Counts of the last frame
// are read back; the first pass in execution order with a non-zero count is where a bad value was
// born. Without the flag this feature declares nothing (zero cost). Depth is not checked.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "../context/render_feature.hpp"

namespace fgb::features {

struct PassFiniteCounts {
  std::string pass;
  uint32_t node = 0;         // the checked pass's node index in the declaration
  uint64_t nan = 0;          // pixels (or samples' pixels) with a NaN in some channel
  uint64_t inf = 0;          // ... with an Inf
  uint64_t overHalfMax = 0;  // ... with a finite |value| > 32752
  [[nodiscard]] bool bad() const { return nan + inf + overHalfMax > 0; }
};

class FiniteCheckFeature final : public IRenderFeature {
 public:
  [[nodiscard]] std::string_view name() const override { return "finite check"; }
  [[nodiscard]] bool enabled() const override { return enabled_; }
  void initialize(FeatureInit& init) override;
  void declare(graph::FrameGraph& graph, Blackboard& board) override;

  // The last rendered frame's counts, one entry per checked pass, in declaration order.
  [[nodiscard]] std::vector<PassFiniteCounts> counts() const;

 private:
  // One texture version a pass wrote, to check.
  struct Written {
    graph::TextureHandle texture;
    graph::Extent extent;
    uint32_t samples = 1;
  };
  struct Checked {
    uint32_t node = 0;
    std::string pass;
    std::vector<Written> textures;
  };

  std::vector<Checked> findCheckedPasses(const graph::FrameGraph& graph) const;
  void declareCheck(graph::FrameGraph& graph, const Checked& checked, uint32_t slot, graph::BufferHandle& counters);

  rhi::Device* device_ = nullptr;
  bool enabled_ = false;
  rhi::PipelineId singleSample_;
  rhi::PipelineId multiSample_;
  rhi::BufferId readback_;
  std::vector<Checked> checked_;
};

}  // namespace fgb::features
