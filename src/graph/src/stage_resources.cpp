// Stages: resolving resource descriptions (dependent fields → values, memory requirements) and
// lifetimes (first/last order position of alive uses), plus the per-queue facts aliasing needs.
#include "compile_state.hpp"

#include <algorithm>
#include <string>

namespace fgb::graph {

MemoryRequirements estimateRequirements(const ResourceDecl& decl, const ResolvedResource& resolved) {
  constexpr uint64_t kAlignment = 256;
  if (decl.kind == ResourceKind::Buffer) return {resolved.buffer.size, kAlignment, ~0u};
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

namespace detail {

void resolveResources(CompileState& state) {
  const auto& decls = state.graph.resources();
  const auto& versions = state.graph.versions();
  auto& resolved = state.out.resources;
  resolved.resize(decls.size());
  // A dependent field can only name a version that existed when the resource was declared, so
  // its source has a smaller index and is already resolved.
  for (size_t r = 0; r < decls.size(); ++r) {
    const ResourceDecl& decl = decls[r];
    ResolvedResource& res = resolved[r];
    res.texture = decl.texture;
    res.buffer = decl.buffer;
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

// Fills state.resourceUses: the uses of each resource by alive nodes, in execution order, one entry
// per (node, resource). Lifetimes come from it here and the barrier plan walks it again.
void collectUsesByResource(CompileState& state) {
  const FrameGraph& graph = state.graph;
  const auto resourceCount = static_cast<uint32_t>(graph.resources().size());
  ResourceUses& lists = state.resourceUses;
  lists.start.assign(resourceCount + 1, 0);
  for (const uint32_t n : state.out.order) {
    for (const Use& use : graph.uses(n)) ++lists.start[use.resource + 1];
  }
  for (uint32_t r = 1; r <= resourceCount; ++r) lists.start[r] += lists.start[r - 1];
  lists.uses.resize(lists.start.back());
  lists.end.assign(lists.start.begin(), lists.start.end() - 1);  // the cursor, and finally each end
  for (const uint32_t n : state.out.order) {
    for (const Use& use : graph.uses(n)) {
      const bool reads = use.readVersion != kInvalidIndex;
      const bool writes = use.writeVersion != kInvalidIndex;
      uint32_t& end = lists.end[use.resource];
      if (end != lists.start[use.resource] && lists.uses[end - 1].node == n) {
        MergedUse& merged = lists.uses[end - 1];  // a node using one resource twice: one combined use
        merged.stages |= use.stages;
        merged.access |= use.accessMask;
        merged.reads |= reads;
        merged.writes |= writes;
        if (merged.layout != use.layout) merged.layout = Layout::General;
        continue;
      }
      lists.uses[end++] = {n, use.stages, use.accessMask, use.layout, reads, writes};
    }
  }
}

}  // namespace

void computeLifetimes(CompileState& state) {
  const auto& decls = state.graph.resources();
  collectUsesByResource(state);
  const ResourceUses& lists = state.resourceUses;
  state.out.lifetimes.assign(decls.size(), {});
  state.out.resourceAlive.assign(decls.size(), false);
  state.lastSigmaOnQueue.assign(decls.size() * kQueueClassCount, 0);
  state.stagesOnQueue.assign(decls.size() * kQueueClassCount, kStageNone);
  state.firstUser.assign(decls.size(), kInvalidIndex);
  for (uint32_t r = 0; r < decls.size(); ++r) {
    const uint32_t begin = lists.start[r];
    const uint32_t end = lists.end[r];
    if (begin == end) continue;
    state.out.resourceAlive[r] = true;
    state.firstUser[r] = lists.uses[begin].node;
    state.out.lifetimes[r] = {state.out.nodes[lists.uses[begin].node].orderIndex,
                              state.out.nodes[lists.uses[end - 1].node].orderIndex};
    for (uint32_t i = begin; i < end; ++i) {
      const uint32_t node = lists.uses[i].node;
      const size_t slot = r * kQueueClassCount + state.queueOf[node];
      state.lastSigmaOnQueue[slot] = std::max(state.lastSigmaOnQueue[slot], state.sigma[node]);
      state.stagesOnQueue[slot] |= lists.uses[i].stages;
    }
  }
  for (size_t r = 0; r < decls.size(); ++r) {
    if (decls[r].imported || !state.out.resourceAlive[r]) continue;
    auto requirements = state.options.requirements ? state.options.requirements(decls[r], state.out.resources[r])
                                                   : estimateRequirements(decls[r], state.out.resources[r]);
    if (requirements.alignment == 0) requirements.alignment = 1;
    state.out.resources[r].requirements = requirements;
  }
}

}  // namespace detail
}  // namespace fgb::graph
