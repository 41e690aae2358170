// Texture formats known to the frame graph. Only what the renderer uses; the backend maps each to
// a VkFormat. Depth formats matter to the graph (aspects and layouts); sizes matter to the memory
// estimate used by tests.
#pragma once

#include <cstdint>
#include <string_view>

namespace fgb::graph {

enum class Format : uint8_t {
  Undefined,
  R8G8B8A8Unorm,
  R8G8B8A8Srgb,
  B8G8R8A8Unorm,
  R16G16B16A16Sfloat,
  R32G32B32A32Sfloat,
  B10G11R11UfloatPack32,
  R16G16Sfloat,
  R32Sfloat,
  R32Uint,
  D32Sfloat,
  D24UnormS8Uint,
  R64Uint,  // 64-bit integer (visibility buffer); storage + atomics only where the device says so
};

bool isDepthFormat(Format format);
bool hasStencil(Format format);
uint32_t bytesPerPixel(Format format);
std::string_view toString(Format format);

}  // namespace fgb::graph
