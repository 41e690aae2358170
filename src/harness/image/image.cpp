#include <fgb/harness/image/image.hpp>

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace fgb::harness {

namespace {

// Reserved (allocated, untouched) storage first, the huge-page hint on it, then the zeros.
template <typename T>
std::vector<T> zeroFilled(std::size_t count) {
  std::vector<T> buffer;
  buffer.reserve(count);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  const std::size_t bytes = count * sizeof(T);
  if (bytes >= 2 * kHugePage) {
    const auto begin = reinterpret_cast<std::uintptr_t>(buffer.data());
    const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
    const std::uintptr_t last = (begin + bytes) & ~(kHugePage - 1);
    // Only a hint: without transparent huge pages the buffer is simply made of small pages.
    if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#endif
  buffer.resize(count, T{});
  return buffer;
}

}  // namespace

std::vector<float> zeroFilledBuffer(std::size_t count) { return zeroFilled<float>(count); }
std::vector<uint8_t> zeroFilledBytes(std::size_t count) { return zeroFilled<uint8_t>(count); }

Image makeImage(uint32_t width, uint32_t height, Encoding encoding) {
  Image image;
  image.width = width;
  image.height = height;
  image.encoding = encoding;
  image.rgba = zeroFilledBuffer(image.pixelCount() * 4);
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

Image shrinkToWidth(const Image& image, uint32_t maxWidth) {
  if (maxWidth == 0 || image.width <= maxWidth) return image;
  const uint32_t factor = (image.width + maxWidth - 1) / maxWidth;
  Image out = makeImage(image.width / factor, image.height / factor, image.encoding);
  const float weight = 1.0f / static_cast<float>(factor * factor);
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = 0; x < out.width; ++x) {
      float* o = &out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4];
      for (uint32_t dy = 0; dy < factor; ++dy) {
        for (uint32_t dx = 0; dx < factor; ++dx) {
          const float* p = &image.rgba[((static_cast<std::size_t>(y) * factor + dy) * image.width + x * factor + dx) * 4];
          for (int c = 0; c < 4; ++c) o[c] += p[c] * weight;
        }
      }
    }
  }
  return out;
}

}  // namespace fgb::harness
