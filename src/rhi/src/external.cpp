#include <fgb/rhi/types.hpp>

namespace fgb::rhi {
namespace {

// ExternalResource ids carry the kind in the high word so a buffer id cannot pass as a texture.
constexpr uint64_t kBufferKind = 1;
constexpr uint64_t kTextureKind = 2;

uint64_t kindOf(graph::ExternalResource resource) { return resource.id >> 32; }
uint32_t indexOf(graph::ExternalResource resource) { return static_cast<uint32_t>(resource.id & 0xffffffffu); }

}  // namespace

graph::ExternalResource external(BufferId buffer) { return {(kBufferKind << 32) | buffer.index}; }
graph::ExternalResource external(TextureId texture) { return {(kTextureKind << 32) | texture.index}; }

BufferId externalBuffer(graph::ExternalResource resource) {
  return kindOf(resource) == kBufferKind ? BufferId{indexOf(resource)} : BufferId{};
}

TextureId externalTexture(graph::ExternalResource resource) {
  return kindOf(resource) == kTextureKind ? TextureId{indexOf(resource)} : TextureId{};
}

}  // namespace fgb::rhi
