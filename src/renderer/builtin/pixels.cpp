#include "pixels.hpp"

#include <glm/gtc/packing.hpp>

#include <cmath>
#include <cstring>

namespace fgb::render {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

ImageRGBA32F fromRgba16f(std::span<const std::byte> texels, uint32_t width, uint32_t height) {
  ImageRGBA32F image{width, height, std::vector<float>(size_t{width} * height * 4)};
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    uint16_t half = 0;
    std::memcpy(&half, texels.data() + i * 2, 2);
    image.pixels[i] = glm::unpackHalf1x16(half);
  }
  return image;
}

ImageRGBA32F fromRgba8Srgb(std::span<const std::byte> texels, uint32_t width, uint32_t height) {
  float table[256];
  for (int v = 0; v < 256; ++v) table[v] = srgbToLinear(static_cast<float>(v) / 255.0f);
  ImageRGBA32F image{width, height, std::vector<float>(size_t{width} * height * 4)};
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const auto byte = std::to_integer<uint8_t>(texels[i]);
    // Alpha is stored linearly in sRGB formats.
    image.pixels[i] = (i % 4 == 3) ? static_cast<float>(byte) / 255.0f : table[byte];
  }
  return image;
}

}  // namespace fgb::render
