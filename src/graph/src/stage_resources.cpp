// Stages: resolving resource descriptions (dependent fields → values, memory requirements) and
// lifetimes (first/last order position of alive uses; the users were found with the dependencies).
#include "compile_state.hpp"

#include <algorithm>
#include <string>

namespace fgb::graph {

namespace {

MemoryRequirements estimate(ResourceKind kind, const ResolvedResource& resolved) {
  constexpr uint64_t kAlignment = 256;
  if (kind == ResourceKind::Buffer) return {resolved.buffer.size, kAlignment, ~0u};
  const TextureDesc& t = resolved.texture;
  uint64_t bytes = 0;
  uint64_t w = t.extent.width, h = t.extent.height, d = t.extent.depth;
  for (uint32_t mip = 0; mip < std::max(1u, t.mipLevels); ++mip) {
    bytes += w * h * d * bytesPerPixel(t.format);
    w = std::max<uint64_t>(1, w / 2);
    h = std::max<uint64_t>(1, h / 2);
    d = std::max<uint64_t>(1, d / 2);
  }
  return {bytes * std::max(1u, t.layers) * std::max(1u, t.samples), kAlignment, ~0u};
}

}  // namespace

MemoryRequirements estimateRequirements(const ResourceDecl& decl, const ResolvedResource& resolved) {
  return estimate(decl.kind, resolved);
}

namespace detail {

void resolveResources(CompileState& state) {
  const auto& decls = state.graph.resources();
  const auto& versions = state.graph.versions();
  auto& resolved = state.out.resources;
  // Appended from the declarations, not default-constructed first and then overwritten: each is
  // written once.
  resolved.clear();
  resolved.reserve(decls.size());
  state.resourceTraits.resize(decls.size());
  // A dependent field can only name a version that existed when the resource was declared, so
  // its source has a smaller index and is already resolved.
  for (size_t r = 0; r < decls.size(); ++r) {
    const ResourceDecl& decl = decls[r];
    ResolvedResource& res = resolved.emplace_back(decl.texture, decl.buffer);
    state.resourceTraits[r] = static_cast<uint8_t>((decl.kind == ResourceKind::Texture ? kResourceTexture : 0) |
                                                   (decl.imported ? kResourceImported : 0));
    if (decl.kind == ResourceKind::Texture && decl.texture.extentFrom.valid()) {
      const TextureDesc& source = resolved[versions[decl.texture.extentFrom.version].resource].texture;
      const uint32_t shift = decl.texture.extentShift;
      res.texture.extent = {std::max(1u, source.extent.width >> shift), std::max(1u, source.extent.height >> shift),
                            std::max(1u, source.extent.depth >> shift)};
      if (res.texture.format == Format::Undefined) res.texture.format = source.format;
      res.texture.extentFrom = {};
    }
    if (decl.kind == ResourceKind::Buffer && decl.buffer.sizeFrom.valid()) {
      res.buffer.size = resolved[versions[decl.buffer.sizeFrom.version].resource].buffer.size;
      res.buffer.sizeFrom = {};
    }
  }
}

namespace {

// estimate() for a run of resources: neighbours often share a description (a chain of
// same-size targets), and then the previous answer is reused.
class EstimateCache {
 public:
  // Sets resolved.requirements (field by field: see add() in stage_barriers.cpp).
  void set(ResolvedResource& resolved, ResourceKind kind) {
    if (!valid_ || kind != kind_ || !sameEstimateInputs(resolved)) {
      kind_ = kind;
      last_ = resolved;
      valid_ = true;
      answer_ = estimate(kind, resolved);
    }
    resolved.requirements.size = answer_.size;
    resolved.requirements.alignment = answer_.alignment;
    resolved.requirements.memoryTypeBits = answer_.memoryTypeBits;
  }

 private:
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

}  // namespace

void computeLifetimes(CompileState& state) {
  const auto& decls = state.graph.resources();
  const uint32_t resources = state.resourceCount;
  auto& lifetimes = state.out.lifetimes;
  lifetimes.assign(resources, {});
  state.firstUser.assign(resources, kInvalidIndex);
  state.lastUser.assign(resources, kInvalidIndex);
  // In execution order: a resource's first user is the first seen, its last the last seen.
  const auto& order = state.out.order;
  for (uint32_t position = 0; position < order.size(); ++position) {
    const uint32_t node = order[position];
    for (const Use& use : state.graph.uses(node)) {
      const uint32_t r = use.resource;
      if (state.firstUser[r] == kInvalidIndex) {
        state.firstUser[r] = node;
        lifetimes[r].first = position;
      }
      state.lastUser[r] = node;
      lifetimes[r].last = position;
    }
  }
  state.out.resourceAlive.assign(resources, false);
  EstimateCache estimates;
  for (uint32_t r = 0; r < resources; ++r) {
    if (state.firstUser[r] == kInvalidIndex) continue;
    state.out.resourceAlive[r] = true;
    if ((state.resourceTraits[r] & kResourceImported) != 0) continue;
    ResolvedResource& resolved = state.out.resources[r];
    if (state.options.requirements) {
      resolved.requirements = state.options.requirements(decls[r], resolved);
    } else {
      estimates.set(resolved, (state.resourceTraits[r] & kResourceTexture) != 0 ? ResourceKind::Texture
                                                                                  : ResourceKind::Buffer);
    }
    if (resolved.requirements.alignment == 0) resolved.requirements.alignment = 1;
  }
}

}  // namespace detail
}  // namespace fgb::graph
