// Memory invariants: resolved dependent fields, requirements, placements, heaps and aliasing.
#include "invariants.hpp"

#include <algorithm>
#include <functional>

namespace fgb::graph::test {
namespace {

uint64_t alignUp(uint64_t value, uint64_t alignment) { return (value + alignment - 1) / alignment * alignment; }

// Resolves a dependent field by walking the declaration (recursion follows dependent sources).
Extent expectedExtent(const FrameGraph& graph, uint32_t resource) {
  const TextureDesc& desc = graph.resources()[resource].texture;
  if (!desc.extentFrom.valid()) return desc.extent;
  const Extent source = expectedExtent(graph, versionsOf(graph)[desc.extentFrom.version].resource);
  auto shifted = [&desc](uint32_t v) { return std::max(1u, v >> desc.extentShift); };
  return {shifted(source.width), shifted(source.height), shifted(source.depth)};
}

uint64_t expectedSize(const FrameGraph& graph, uint32_t resource) {
  const BufferDesc& desc = graph.resources()[resource].buffer;
  if (!desc.sizeFrom.valid()) return desc.size;
  return expectedSize(graph, versionsOf(graph)[desc.sizeFrom.version].resource);
}

MemoryRequirements requirementsFor(const CompileOptions& options, const ResourceDecl& decl,
                                   const ResolvedResource& resolved) {
  return options.requirements ? options.requirements(decl, resolved) : estimateRequirements(decl, resolved);
}

std::vector<std::vector<uint32_t>> usersOf(const GraphModel& model, const CompiledGraph& compiled) {
  std::vector<std::vector<uint32_t>> users(model.resourceCount());
  for (const ModelUse& use : model.uses) {
    if (!compiled.nodes[use.node].culled) users[use.resource].push_back(use.node);
  }
  return users;
}

bool allBefore(const HappensBefore& hb, const std::vector<uint32_t>& first, const std::vector<uint32_t>& second) {
  for (uint32_t a : first) {
    for (uint32_t b : second) {
      if (!hb.ordered(a, b)) return false;
    }
  }
  return true;
}

Problems checkPlacement(const GraphModel& model, const FrameGraph& graph, const CompiledGraph& compiled,
                        const CompileOptions& options, uint32_t r) {
  const ResourceDecl& decl = graph.resources()[r];
  const Placement& placement = compiled.aliasing.placements[r];
  const std::string what = "resource '" + model.resourceName[r] + "'";
  const bool needsMemory = !decl.imported && compiled.resourceAlive[r];
  if (!needsMemory) return placement.heap == kInvalidIndex ? Problems{} : Problems{what + " placed but needs no memory"};
  if (placement.heap >= compiled.aliasing.heaps.size()) return {what + " has no heap"};
  const MemoryRequirements req = requirementsFor(options, decl, compiled.resources[r]);
  const MemoryRequirements& got = compiled.resources[r].requirements;
  Problems problems;
  if (got.size != req.size || got.alignment != req.alignment || got.memoryTypeBits != req.memoryTypeBits) {
    problems.push_back(what + ": requirements differ from the requirements callback");
  }
  const Heap& heap = compiled.aliasing.heaps[placement.heap];
  if (placement.size < req.size) problems.push_back(what + ": placement smaller than required");
  if (placement.offset % req.alignment != 0) problems.push_back(what + ": offset not aligned");
  if (placement.offset + placement.size > heap.size) problems.push_back(what + ": placement past the heap end");
  if (heap.memoryTypeBits == 0 || (heap.memoryTypeBits & ~req.memoryTypeBits) != 0) {
    problems.push_back(what + ": heap memory types not allowed for it");
  }
  if (heap.kind != decl.kind) problems.push_back(what + ": placed in a heap of the other kind");
  return problems;
}

bool rangesOverlap(const Placement& a, const Placement& b) {
  return a.heap == b.heap && a.offset < b.offset + b.size && b.offset < a.offset + a.size;
}

Problems checkOverlaps(const GraphModel& model, const CompiledGraph& compiled, const CompileOptions& options) {
  Problems problems;
  const HappensBefore hb(compiled);
  const auto users = usersOf(model, compiled);
  const auto& placements = compiled.aliasing.placements;
  for (uint32_t a = 0; a < placements.size(); ++a) {
    for (uint32_t b = a + 1; b < placements.size(); ++b) {
      if (placements[a].heap == kInvalidIndex || !rangesOverlap(placements[a], placements[b])) continue;
      const std::string pair = "'" + model.resourceName[a] + "' and '" + model.resourceName[b] + "'";
      if (!options.alias) problems.push_back(pair + " share memory with aliasing off");
      const Lifetime& la = compiled.lifetimes[a];
      const Lifetime& lb = compiled.lifetimes[b];
      if (!(la.last < lb.first || lb.last < la.first)) problems.push_back(pair + " share memory while both live");
      if (!allBefore(hb, users[a], users[b]) && !allBefore(hb, users[b], users[a])) {
        problems.push_back(pair + " share memory but their uses are not ordered on the GPU");
      }
    }
  }
  return problems;
}

}  // namespace

Problems checkResolvedFields(const FrameGraph& graph, const CompiledGraph& compiled) {
  if (compiled.resources.size() != graph.resources().size()) return {"resolved resources sized wrong"};
  Problems problems;
  for (uint32_t r = 0; r < graph.resources().size(); ++r) {
    const ResourceDecl& decl = graph.resources()[r];
    if (decl.kind == ResourceKind::Texture) {
      const Extent want = expectedExtent(graph, r);
      const Extent got = compiled.resources[r].texture.extent;
      if (got.width != want.width || got.height != want.height || got.depth != want.depth) {
        problems.push_back("texture '" + std::string(decl.name) + "': extent not resolved from its dependent field");
      }
    } else if (compiled.resources[r].buffer.size != expectedSize(graph, r)) {
      problems.push_back("buffer '" + std::string(decl.name) + "': size not resolved from its dependent field");
    }
  }
  return problems;
}

Problems checkAliasing(const GraphModel& model, const FrameGraph& graph, const CompiledGraph& compiled,
                       const CompileOptions& options) {
  const AliasingPlan& plan = compiled.aliasing;
  if (plan.placements.size() != graph.resources().size()) return {"placements sized wrong"};
  Problems problems;
  uint64_t unaliased = 0;
  for (uint32_t r = 0; r < graph.resources().size(); ++r) {
    const Problems some = checkPlacement(model, graph, compiled, options, r);
    problems.insert(problems.end(), some.begin(), some.end());
    if (!graph.resources()[r].imported && compiled.resourceAlive[r]) {
      const MemoryRequirements req = requirementsFor(options, graph.resources()[r], compiled.resources[r]);
      unaliased += alignUp(req.size, req.alignment);
    }
  }
  if (!problems.empty()) return problems;
  uint64_t heapBytes = 0;
  for (const Heap& heap : plan.heaps) heapBytes += heap.size;
  if (plan.peakBytesAliased != heapBytes) problems.push_back("peakBytesAliased != sum of heap sizes");
  if (plan.peakBytesUnaliased != unaliased) {
    problems.push_back("peakBytesUnaliased " + std::to_string(plan.peakBytesUnaliased) + " != " +
                       std::to_string(unaliased) + " (alive transients, aligned)");
  }
  const Problems overlaps = checkOverlaps(model, compiled, options);
  problems.insert(problems.end(), overlaps.begin(), overlaps.end());
  return problems;
}

}  // namespace fgb::graph::test
