#include <fgb/harness/metrics/metrics.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace fgb::harness {
namespace {

// Key colours of the magma colour map (sRGB, 0..255) at t = 0, 1/8, ..., 1; interpolated linearly.
constexpr std::array<std::array<float, 3>, 9> kMagmaKeys{{
    {0, 0, 4}, {28, 16, 68}, {79, 18, 123}, {129, 37, 129}, {181, 54, 122},
    {229, 80, 100}, {251, 135, 97}, {254, 194, 135}, {252, 253, 191},
}};

std::array<float, 3> magma(float t) {
  const float clamped = std::isfinite(t) ? std::clamp(t, 0.0f, 1.0f) : 1.0f;
  const float position = clamped * static_cast<float>(kMagmaKeys.size() - 1);
  const auto index = std::min(static_cast<std::size_t>(position), kMagmaKeys.size() - 2);
  const float f = position - static_cast<float>(index);
  std::array<float, 3> c{};
  for (int k = 0; k < 3; ++k) c[k] = (kMagmaKeys[index][k] * (1.0f - f) + kMagmaKeys[index + 1][k] * f) / 255.0f;
  return c;
}

}  // namespace

Image heatMap(const std::vector<float>& errors, const std::vector<uint8_t>& nonFiniteMask, uint32_t width, uint32_t height) {
  Image image = makeImage(width, height, Encoding::Srgb);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    const bool broken = i < nonFiniteMask.size() && nonFiniteMask[i];
    const std::array<float, 3> c = broken ? std::array<float, 3>{0.0f, 1.0f, 0.0f} : magma(i < errors.size() ? errors[i] : 0.0f);
    float* p = &image.rgba[i * 4];
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
    p[3] = 1.0f;
  }
  return image;
}

}  // namespace fgb::harness
