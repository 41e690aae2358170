#include <Imath/half.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfThreading.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/harness/base/parallel.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fstream>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>

#include "exr_fast_reader.hpp"

namespace fgb::harness {
namespace {

std::string lowercaseExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void requireReadableFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path.string() + ": no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string() + ": not a regular file");
}

// OpenEXR decodes ZIP blocks in parallel when given a thread pool; set it up once.
void enableExrThreads() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))); });
}

}  // namespace


ImageFormat detectImageFormat(const std::filesystem::path& path) {
  const std::string ext = lowercaseExtension(path);
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".png") return ImageFormat::Png;
  requireReadableFile(path);
  std::array<unsigned char, 8> magic{};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(magic.data()), magic.size());
  static constexpr std::array<unsigned char, 4> kExrMagic{0x76, 0x2f, 0x31, 0x01};
  static constexpr std::array<unsigned char, 8> kPngMagic{0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  if (std::equal(kExrMagic.begin(), kExrMagic.end(), magic.begin())) return ImageFormat::Exr;
  if (std::equal(kPngMagic.begin(), kPngMagic.end(), magic.begin())) return ImageFormat::Png;
  throw InputError(path.string() + ": not an OpenEXR or PNG image");
}

Image readImage(const std::filesystem::path& path) {
  return detectImageFormat(path) == ImageFormat::Exr ? readExr(path) : readPng(path);
}

namespace {

// Plain R, G, B (and A) channels at full resolution: OpenEXR converts them to float straight into
// the image (the general RGBA interface would go through an intermediate half-float copy).
bool hasFullResolutionRgb(const Imf::Header& header) {
  const Imf::ChannelList& channels = header.channels();
  bool any = false;
  for (const char* name : {"R", "G", "B", "A"}) {
    const Imf::Channel* channel = channels.findChannel(name);
    if (!channel) continue;
    if (channel->xSampling != 1 || channel->ySampling != 1) return false;
    any = any || name[0] != 'A';
  }
  return any;
}

}  // namespace

std::pair<Image, Image> readImagePair(const std::filesystem::path& a, const std::filesystem::path& b) {
  // OpenEXR decodes on its own thread pool; reading the files side by side also overlaps what each
  // read does on its calling thread (file access, allocation, PNG decoding).
  std::future<Image> first = std::async(std::launch::async, [&a] { return readImage(a); });
  std::exception_ptr secondFailure;
  Image second;
  try {
    second = readImage(b);
  } catch (...) {
    secondFailure = std::current_exception();
  }
  Image firstImage = first.get();  // rethrows a's error first, as reading a then b would
  if (secondFailure) std::rethrow_exception(secondFailure);
  return {std::move(firstImage), std::move(second)};
}

Image readExr(const std::filesystem::path& path) {
  requireReadableFile(path);
  try {
    if (std::optional<Image> image = detail::readExrFast(path)) return std::move(*image);
  } catch (const std::exception&) {
    // Whatever the fast reader trips over (an absurd size in a damaged header), OpenEXR reports.
  }
  enableExrThreads();
  try {
    {
      Imf::InputFile file(path.c_str());
      if (hasFullResolutionRgb(file.header())) {
        const Imath::Box2i window = file.header().dataWindow();
        const long width = static_cast<long>(window.max.x) - window.min.x + 1;
        const long height = static_cast<long>(window.max.y) - window.min.y + 1;
        if (width <= 0 || height <= 0) throw InputError(path.string() + ": empty data window");
        Image image = makeImage(static_cast<uint32_t>(width), static_cast<uint32_t>(height), Encoding::Linear);
        constexpr std::size_t xStride = 4 * sizeof(float);
        const std::size_t yStride = xStride * static_cast<std::size_t>(width);
        // The frame buffer is addressed by absolute pixel coordinates.
        char* base = reinterpret_cast<char*>(image.rgba.data()) - static_cast<std::ptrdiff_t>(window.min.x) * static_cast<std::ptrdiff_t>(xStride) -
                     static_cast<std::ptrdiff_t>(window.min.y) * static_cast<std::ptrdiff_t>(yStride);
        Imf::FrameBuffer frameBuffer;
        const std::array<const char*, 4> names{"R", "G", "B", "A"};
        for (std::size_t c = 0; c < names.size(); ++c) {
          // Missing channels: 0 for colour, opaque alpha (as the RGBA interface fills them).
          frameBuffer.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride, 1, 1, c == 3 ? 1.0 : 0.0));
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
        return image;
      }
    }
    // Anything else (luminance/chroma, subsampled channels): OpenEXR's RGBA interface converts it.
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i window = file.dataWindow();
    const long width = static_cast<long>(window.max.x) - window.min.x + 1;
    const long height = static_cast<long>(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0) throw InputError(path.string() + ": empty data window");
    Imf::Array2D<Imf::Rgba> pixels(height, width);
    const auto base = static_cast<std::ptrdiff_t>(window.min.x) + static_cast<std::ptrdiff_t>(window.min.y) * width;
    file.setFrameBuffer(&pixels[0][0] - base, 1, static_cast<std::size_t>(width));
    file.readPixels(window.min.y, window.max.y);

    Image image = makeImage(static_cast<uint32_t>(width), static_cast<uint32_t>(height), Encoding::Linear);
    const bool hasAlpha = (file.channels() & Imf::WRITE_A) != 0;
    float* out = image.rgba.data();
    for (long y = 0; y < height; ++y) {
      for (long x = 0; x < width; ++x, out += 4) {
        const Imf::Rgba& p = pixels[y][x];
        out[0] = p.r;
        out[1] = p.g;
        out[2] = p.b;
        out[3] = hasAlpha ? static_cast<float>(p.a) : 1.0f;
      }
    }
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::string reason = e.what();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(path.string() + ": not a readable OpenEXR image (" + reason + ")");
  }
}

Image readPng(const std::filesystem::path& path) {
  requireReadableFile(path);
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&png, path.c_str()) == 0) {
    throw InputError(path.string() + ": not a readable PNG image (" + png.message + ")");
  }
  png.format = PNG_FORMAT_RGBA;  // 8-bit sRGB; libpng converts grey, palette and 16-bit input
  std::vector<unsigned char> bytes(PNG_IMAGE_SIZE(png));
  if (png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr) == 0) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw InputError(path.string() + ": corrupt PNG image (" + reason + ")");
  }
  Image image = makeImage(png.width, png.height, Encoding::Srgb);
  std::transform(bytes.begin(), bytes.end(), image.rgba.begin(), [](unsigned char b) { return static_cast<float>(b) / 255.0f; });
  return image;
}

void writeExr(const std::filesystem::path& path, const Image& linear) {
  enableExrThreads();
  std::vector<Imf::Rgba> pixels(linear.pixelCount());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const float* p = &linear.rgba[i * 4];
    pixels[i] = Imf::Rgba(p[0], p[1], p[2], p[3]);
  }
  writeViaTemporary(path, [&](const std::filesystem::path& temporary) {
    Imf::RgbaOutputFile file(temporary.c_str(), static_cast<int>(linear.width), static_cast<int>(linear.height),
                             Imf::WRITE_RGBA, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, Imf::ZIP_COMPRESSION);
    file.setFrameBuffer(pixels.data(), 1, linear.width);
    file.writePixels(static_cast<int>(linear.height));
  });
}

void writeExrFloat(const std::filesystem::path& path, const Image& linear, int channels) {
  if (channels < 1 || channels > 4) throw std::invalid_argument("writeExrFloat: 1 to 4 channels");
  enableExrThreads();
  const std::array<const char*, 4> names{"R", "G", "B", "A"};
  writeViaTemporary(path, [&](const std::filesystem::path& temporary) {
    Imf::Header header(static_cast<int>(linear.width), static_cast<int>(linear.height));
    header.compression() = Imf::ZIP_COMPRESSION;
    for (int c = 0; c < channels; ++c) header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(temporary.c_str(), header);
    Imf::FrameBuffer frameBuffer;
    constexpr std::size_t xStride = 4 * sizeof(float);
    const std::size_t yStride = xStride * linear.width;
    auto* base = reinterpret_cast<char*>(const_cast<float*>(linear.rgba.data()));
    for (int c = 0; c < channels; ++c)
      frameBuffer.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
    file.setFrameBuffer(frameBuffer);
    file.writePixels(static_cast<int>(linear.height));
  });
}

namespace {
// 8-bit RGB bytes of an image as PNG files store them (sRGB-encoded, clamped).
std::vector<unsigned char> pngBytes(const Image& image) {
  const Image encoded = quantizeToSrgb8(image);
  std::vector<unsigned char> bytes(image.pixelCount() * 3);
  for (std::size_t i = 0; i < image.pixelCount(); ++i) {
    for (int c = 0; c < 3; ++c) {
      bytes[i * 3 + c] = static_cast<unsigned char>(std::lround(encoded.rgba[i * 4 + c] * 255.0f));
    }
  }
  return bytes;
}

png_image pngHeader(const Image& image) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGB;
  return png;
}
}  // namespace

void writePng(const std::filesystem::path& path, const Image& image) {
  const std::vector<unsigned char> bytes = pngBytes(image);
  writeViaTemporary(path, [&](const std::filesystem::path& temporary) {
    png_image png = pngHeader(image);
    if (png_image_write_to_file(&png, temporary.c_str(), 0, bytes.data(), 0, nullptr) == 0) {
      const std::string reason = png.message;
      png_image_free(&png);
      throw std::runtime_error(path.string() + ": cannot write PNG (" + reason + ")");
    }
  });
}

std::vector<uint8_t> encodePng(const Image& image) {
  const std::vector<unsigned char> bytes = pngBytes(image);
  png_image png = pngHeader(image);
  png_alloc_size_t size = 0;
  // First call measures, second writes (libpng's documented two-step use).
  if (png_image_write_to_memory(&png, nullptr, &size, 0, bytes.data(), 0, nullptr) == 0) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw std::runtime_error("cannot encode PNG (" + reason + ")");
  }
  std::vector<uint8_t> out(size);
  if (png_image_write_to_memory(&png, out.data(), &size, 0, bytes.data(), 0, nullptr) == 0) {
    const std::string reason = png.message;
    png_image_free(&png);
    throw std::runtime_error("cannot encode PNG (" + reason + ")");
  }
  out.resize(size);
  return out;
}

}  // namespace fgb::harness
