// Stage: resolving resource descriptions (dependent fields → values). The memory requirements of
// alive transients are asked for where placement needs them (see TransientPlacer::place).
#include <algorithm>
#include <string>

#include "compile_state.hpp"

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
  const auto& versions = state.versions();
  auto& resolved = state.out.resources;
  resolved.clear();
  // A dependent field can only name a version that existed when the resource was declared, so
  // its source has a smaller index and is already resolved.
  for (size_t r = 0; r < decls.size(); ++r) {
    const ResourceDecl& decl = decls[r];
    ResolvedResource& res = resolved.emplace_back(decl.texture, decl.buffer);
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

}  // namespace detail
}  // namespace fgb::graph
