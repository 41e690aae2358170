// Internal: the memory requirements of a transient, asked for by placement at its first use (so
// culled resources never reach CompileOptions::requirements, which may query the device).
#pragma once

#include "compile_state.hpp"

namespace fgb::graph::detail {

// estimateRequirements() by kind (defined in stage_resources.cpp).
MemoryRequirements estimateFor(ResourceKind kind, const ResolvedResource& resolved);

// Sets resolved.requirements from CompileOptions::requirements, or the estimate without one. The
// estimate of a run of resources is reused while their descriptions agree (neighbours are often
// same-size targets).
class RequirementsResolver {
 public:
  void resolve(const CompileState& state, uint32_t resource, ResolvedResource& resolved) {
    if (state.options.requirements) {
      resolved.requirements = state.options.requirements(state.graph.resources()[resource], resolved);
    } else {
      setEstimate(resolved, state.kindOf(resource));
    }
    if (resolved.requirements.alignment == 0) resolved.requirements.alignment = 1;
  }

 private:
  // Field by field: see addBefore() in stage_barriers.cpp.
  void setEstimate(ResolvedResource& resolved, ResourceKind kind) {
    if (!valid_ || kind != kind_ || !sameEstimateInputs(resolved)) {
      kind_ = kind;
      last_ = resolved;
      valid_ = true;
      answer_ = estimateFor(kind, resolved);
    }
    resolved.requirements.size = answer_.size;
    resolved.requirements.alignment = answer_.alignment;
    resolved.requirements.memoryTypeBits = answer_.memoryTypeBits;
  }

  // Everything estimateRequirements() reads.
  [[nodiscard]] bool sameEstimateInputs(const ResolvedResource& r) const {
    if (kind_ == ResourceKind::Buffer) return r.buffer.size == last_.buffer.size;
    const TextureDesc& a = r.texture;
    const TextureDesc& b = last_.texture;
    return a.format == b.format && a.extent.width == b.extent.width && a.extent.height == b.extent.height &&
           a.extent.depth == b.extent.depth && a.mipLevels == b.mipLevels && a.layers == b.layers &&
           a.samples == b.samples;
  }

  bool valid_ = false;
  ResourceKind kind_ = ResourceKind::Texture;
  ResolvedResource last_{};
  MemoryRequirements answer_{};
};

}  // namespace fgb::graph::detail
