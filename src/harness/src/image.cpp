#include <fgb/harness/image.hpp>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>

namespace fgb::harness {

Image makeImage(uint32_t width, uint32_t height, Encoding encoding) {
  Image image;
  image.width = width;
  image.height = height;
  image.encoding = encoding;
  image.rgba.assign(image.pixelCount() * 4, 0.0f);
  return image;
}

Image fromRendered(const render::ImageRGBA32F& rendered, Encoding encoding) {
  Image image;
  image.width = rendered.width;
  image.height = rendered.height;
  image.rgba = rendered.pixels;
  image.rgba.resize(image.pixelCount() * 4, 0.0f);
  image.encoding = encoding;
  return image;
}

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

Image toEncoding(const Image& image, Encoding encoding) {
  if (image.encoding == encoding) return image;
  Image out = image;
  out.encoding = encoding;
  const auto convert = encoding == Encoding::Srgb ? linearToSrgb : srgbToLinear;
  for (std::size_t i = 0; i < out.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) out.rgba[i + c] = convert(out.rgba[i + c]);
  }
  return out;
}

Image quantizeToSrgb8(const Image& image) {
  Image out = toEncoding(image, Encoding::Srgb);
  for (float& v : out.rgba) {
    const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    v = std::round(clamped * 255.0f) / 255.0f;
  }
  return out;
}

Image quantizeToHalf(const Image& linear) {
  Image out = linear;
  for (float& v : out.rgba) v = static_cast<float>(Imath::half(v));
  return out;
}

std::size_t countNonFinite(const Image& image) {
  std::size_t count = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    if (!std::isfinite(image.rgba[i]) || !std::isfinite(image.rgba[i + 1]) || !std::isfinite(image.rgba[i + 2])) {
      ++count;
    }
  }
  return count;
}

std::string describeSize(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

}  // namespace fgb::harness
