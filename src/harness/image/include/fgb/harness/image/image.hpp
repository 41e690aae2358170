// The harness' image: RGBA float pixels with the encoding they are stored in. EXR files and the
// renderer's HDR output are linear; PNG files hold sRGB-encoded values in [0, 1].
#pragma once

#include <fgb/renderer/workload.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fgb::harness {

enum class Encoding { Linear, Srgb };

struct Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;  // width * height * 4, row-major, top row first
  Encoding encoding = Encoding::Linear;

  std::size_t pixelCount() const { return static_cast<std::size_t>(width) * height; }
};

Image makeImage(uint32_t width, uint32_t height, Encoding encoding);

// `count` zeros. Large buffers are backed by transparent huge pages where the OS offers them: for
// 4K images, first-touch page faults on 4 KiB pages cost as much as some of the metrics.
std::vector<float> zeroFilledBuffer(std::size_t count);
std::vector<uint8_t> zeroFilledBytes(std::size_t count);

Image fromRendered(const render::ImageRGBA32F& rendered, Encoding encoding = Encoding::Linear);

float srgbToLinear(float encoded);
float linearToSrgb(float linear);  // clamps to [0, 1] first

// The same image re-encoded (RGB; alpha unchanged). Linear -> sRGB clamps to [0, 1].
Image toEncoding(const Image& image, Encoding encoding);

// Exactly what writePng stores / writeExr stores, so in-memory results compare bit-exactly with a
// golden written by the same code: sRGB 8-bit (from a linear or sRGB image) and half floats.
Image quantizeToSrgb8(const Image& image);
Image quantizeToHalf(const Image& linear);

// NaN or Inf in any RGB channel.
std::size_t countNonFinite(const Image& image);

std::string describeSize(const Image& image);

// The image shrunk by an integer factor (box filter over factor x factor blocks, in its own
// encoding) so that it is at most maxWidth wide; the image itself when it already is.
Image shrinkToWidth(const Image& image, uint32_t maxWidth);  // "640x360"

}  // namespace fgb::harness
