// OpenImageIO decoding to RGBA8.
#include "image_decode.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>

namespace fgb::import {
namespace {

// Expands 1-4 channels to RGBA.
std::vector<uint8_t> toRgba(const std::vector<uint8_t>& pixels, uint32_t width, uint32_t height, int channels) {
  std::vector<uint8_t> rgba(size_t(width) * height * 4);
  for (size_t i = 0; i < size_t(width) * height; ++i) {
    const uint8_t* in = &pixels[i * size_t(channels)];
    uint8_t* out = &rgba[i * 4];
    if (channels <= 2) {
      out[0] = out[1] = out[2] = in[0];
      out[3] = channels == 2 ? in[1] : 255;
    } else {
      out[0] = in[0];
      out[1] = in[1];
      out[2] = in[2];
      out[3] = channels >= 4 ? in[3] : 255;
    }
  }
  return rgba;
}

std::optional<DecodedImage> readAll(OIIO::ImageInput& input, std::string& error) {
  const OIIO::ImageSpec& spec = input.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
    error = "unsupported image dimensions";
    return std::nullopt;
  }
  const int channels = std::min(spec.nchannels, 4);
  std::vector<uint8_t> pixels(size_t(spec.width) * size_t(spec.height) * size_t(channels));
  if (!input.read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data())) {
    error = input.geterror();
    return std::nullopt;
  }
  DecodedImage image;
  image.width = static_cast<uint32_t>(spec.width);
  image.height = static_cast<uint32_t>(spec.height);
  image.rgba = toRgba(pixels, image.width, image.height, channels);
  return image;
}

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

}  // namespace

std::optional<DecodedImage> decodeImageFile(const std::filesystem::path& path, std::string& error) {
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(path, ignored)) {
    error = "file not found";
    return std::nullopt;
  }
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    error = oneLine(OIIO::geterror());
    return std::nullopt;
  }
  auto image = readAll(*input, error);
  error = oneLine(error);
  return image;
}

std::optional<DecodedImage> decodeImageMemory(std::span<const uint8_t> bytes, const std::string& formatHint,
                                              std::string& error) {
  OIIO::Filesystem::IOMemReader reader(bytes.data(), bytes.size());
  auto input = OIIO::ImageInput::open("embedded." + (formatHint.empty() ? std::string("png") : formatHint), nullptr,
                                      &reader);
  if (!input) {
    error = oneLine(OIIO::geterror());
    return std::nullopt;
  }
  auto image = readAll(*input, error);
  error = oneLine(error);
  return image;
}

}  // namespace fgb::import
