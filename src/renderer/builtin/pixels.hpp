// Conversions of read-back pixels to the Workload's linear float RGBA.
#pragma once

#include <fgb/renderer/workload.hpp>

#include <cstddef>
#include <span>

namespace fgb::render {

// RGBA16F texels (tightly packed rows, top row first).
ImageRGBA32F fromRgba16f(std::span<const std::byte> texels, uint32_t width, uint32_t height);
// RGBA8 sRGB-encoded texels, decoded to linear.
ImageRGBA32F fromRgba8Srgb(std::span<const std::byte> texels, uint32_t width, uint32_t height);
float srgbToLinear(float encoded);

}  // namespace fgb::render
