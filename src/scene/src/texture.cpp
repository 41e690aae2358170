// Mip chain construction (2x2 box filter, odd sizes clamp) and the fallback texture.
#include <fgb/scene/texture.hpp>

#include <fgb/core/error.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace fgb::scene {
namespace {

const std::array<float, 256>& srgbToLinearTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const float c = static_cast<float>(i) / 255.0f;
      t[static_cast<size_t>(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    return t;
  }();
  return table;
}

uint8_t linearToSrgb(float linear) {
  const float c = linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return static_cast<uint8_t>(std::clamp(c * 255.0f + 0.5f, 0.0f, 255.0f));
}

uint8_t toByte(float value) { return static_cast<uint8_t>(std::clamp(value + 0.5f, 0.0f, 255.0f)); }

// Averages the (up to) 2x2 source texels under each destination texel.
void downsample(const uint8_t* src, uint32_t srcW, uint32_t srcH, uint8_t* dst, uint32_t dstW, uint32_t dstH,
                bool srgb) {
  const auto& toLinear = srgbToLinearTable();
  for (uint32_t y = 0; y < dstH; ++y) {
    const uint32_t y0 = std::min(2 * y, srcH - 1), y1 = std::min(2 * y + 1, srcH - 1);
    for (uint32_t x = 0; x < dstW; ++x) {
      const uint32_t x0 = std::min(2 * x, srcW - 1), x1 = std::min(2 * x + 1, srcW - 1);
      const uint8_t* taps[4] = {src + (size_t(y0) * srcW + x0) * 4, src + (size_t(y0) * srcW + x1) * 4,
                                src + (size_t(y1) * srcW + x0) * 4, src + (size_t(y1) * srcW + x1) * 4};
      uint8_t* out = dst + (size_t(y) * dstW + x) * 4;
      for (int c = 0; c < 4; ++c) {
        float sum = 0.0f;
        const bool colour = srgb && c < 3;  // alpha is always linear
        for (const uint8_t* tap : taps) sum += colour ? toLinear[tap[c]] : float(tap[c]);
        out[c] = colour ? linearToSrgb(sum * 0.25f) : toByte(sum * 0.25f);
      }
    }
  }
}

}  // namespace

uint32_t mipLevelCount(uint32_t width, uint32_t height) {
  uint32_t levels = 1;
  for (uint32_t size = std::max(width, height); size > 1; size /= 2) ++levels;
  return levels;
}

Texture makeTexture(std::string name, uint32_t width, uint32_t height, std::vector<uint8_t> rgba, bool srgb) {
  if (width == 0 || height == 0 || rgba.size() != size_t(width) * height * 4) {
    throw InputError(name + ": image has size " + std::to_string(width) + "x" + std::to_string(height) +
                     " but " + std::to_string(rgba.size()) + " bytes of RGBA8 data");
  }
  Texture texture;
  texture.name = std::move(name);
  texture.width = width;
  texture.height = height;
  texture.srgb = srgb;
  const uint32_t levels = mipLevelCount(width, height);
  size_t total = 0;
  for (uint32_t level = 0, w = width, h = height; level < levels; ++level) {
    texture.mips.push_back(MipLevel{w, h, total});
    total += size_t(w) * h * 4;
    w = std::max(1u, w / 2);
    h = std::max(1u, h / 2);
  }
  texture.data = std::move(rgba);
  texture.data.resize(total);
  for (uint32_t level = 1; level < levels; ++level) {
    const MipLevel& src = texture.mips[level - 1];
    const MipLevel& dst = texture.mips[level];
    downsample(texture.data.data() + src.offset, src.width, src.height, texture.data.data() + dst.offset,
               dst.width, dst.height, srgb);
  }
  return texture;
}

Texture fallbackTexture(const std::string& missingName, bool srgb) {
  constexpr uint32_t kSize = 64, kCell = 8;
  std::vector<uint8_t> texels(size_t(kSize) * kSize * 4);
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const bool magenta = ((x / kCell) + (y / kCell)) % 2 == 0;
      uint8_t* t = &texels[(size_t(y) * kSize + x) * 4];
      t[0] = magenta ? 255 : 0;
      t[1] = 0;
      t[2] = magenta ? 255 : 0;
      t[3] = 255;
    }
  }
  return makeTexture("fallback:" + missingName, kSize, kSize, std::move(texels), srgb);
}

}  // namespace fgb::scene
