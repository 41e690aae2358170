#include <fgb/graph/format.hpp>

namespace fgb::graph {

bool isDepthFormat(Format format) { return format == Format::D32Sfloat || format == Format::D24UnormS8Uint; }

bool hasStencil(Format format) { return format == Format::D24UnormS8Uint; }

uint32_t bytesPerPixel(Format format) {
  switch (format) {
    case Format::Undefined: return 0;
    case Format::R8G8B8A8Unorm:
    case Format::R8G8B8A8Srgb:
    case Format::B8G8R8A8Unorm:
    case Format::B10G11R11UfloatPack32:
    case Format::R16G16Sfloat:
    case Format::R32Sfloat:
    case Format::R32Uint:
    case Format::D32Sfloat:
    case Format::D24UnormS8Uint: return 4;
    case Format::R16G16B16A16Sfloat:
    case Format::R64Uint: return 8;
    case Format::R32G32B32A32Sfloat: return 16;
  }
  return 0;
}

std::string_view toString(Format format) {
  switch (format) {
    case Format::Undefined: return "UNDEFINED";
    case Format::R8G8B8A8Unorm: return "R8G8B8A8_UNORM";
    case Format::R8G8B8A8Srgb: return "R8G8B8A8_SRGB";
    case Format::B8G8R8A8Unorm: return "B8G8R8A8_UNORM";
    case Format::R16G16B16A16Sfloat: return "R16G16B16A16_SFLOAT";
    case Format::R32G32B32A32Sfloat: return "R32G32B32A32_SFLOAT";
    case Format::B10G11R11UfloatPack32: return "B10G11R11_UFLOAT_PACK32";
    case Format::R16G16Sfloat: return "R16G16_SFLOAT";
    case Format::R32Sfloat: return "R32_SFLOAT";
    case Format::R32Uint: return "R32_UINT";
    case Format::D32Sfloat: return "D32_SFLOAT";
    case Format::D24UnormS8Uint: return "D24_UNORM_S8_UINT";
    case Format::R64Uint: return "R64_UINT";
  }
  return "?";
}

}  // namespace fgb::graph
