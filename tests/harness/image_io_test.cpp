#include <fgb/core/error.hpp>
#include <fgb/harness/image/image_io.hpp>

#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Imath/half.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <utility>

namespace fgb::harness {
namespace {

using ::testing::HasSubstr;

Image gradient(uint32_t w, uint32_t h, float scaleBy) {
  Image image = makeImage(w, h, Encoding::Linear);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      float* p = &image.rgba[(static_cast<std::size_t>(y) * w + x) * 4];
      p[0] = scaleBy * static_cast<float>(x) / static_cast<float>(w);
      p[1] = scaleBy * static_cast<float>(y) / static_cast<float>(h);
      p[2] = 0.25f;
      p[3] = 1.0f;
    }
  }
  return image;
}

TEST(ImageIo, ExrRoundTripKeepsHalfPrecisionValues) {
  testing::ScratchDir dir;
  const Image original = gradient(17, 9, 40.0f);  // HDR values above 1
  writeExr(dir / "a.exr", original);
  const Image back = readImage(dir / "a.exr");
  ASSERT_EQ(back.width, 17u);
  ASSERT_EQ(back.height, 9u);
  EXPECT_EQ(back.encoding, Encoding::Linear);
  EXPECT_EQ(back.rgba, quantizeToHalf(original).rgba);
}

TEST(ImageIo, PngRoundTripStoresSrgb8) {
  testing::ScratchDir dir;
  const Image original = gradient(13, 7, 1.0f);
  writePng(dir / "a.png", original);
  const Image back = readImage(dir / "a.png");
  EXPECT_EQ(back.encoding, Encoding::Srgb);
  const Image expected = quantizeToSrgb8(original);
  ASSERT_EQ(back.rgba.size(), expected.rgba.size());
  for (std::size_t i = 0; i < back.rgba.size(); i += 4) {
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(back.rgba[i + c], expected.rgba[i + c]);
    EXPECT_FLOAT_EQ(back.rgba[i + 3], 1.0f);  // RGB PNG reads back opaque
  }
}

TEST(ImageIo, SrgbCurveRoundTrips) {
  for (float v : {0.0f, 0.002f, 0.1f, 0.5f, 1.0f}) EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-6f);
  EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);
}

TEST(ImageIo, MissingFileIsInputErrorNamingIt) {
  testing::ScratchDir dir;
  try {
    readImage(dir / "nope.exr");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nope.exr"));
    EXPECT_THAT(e.what(), HasSubstr("no such file"));
  }
}

TEST(ImageIo, CorruptFilesAreInputErrors) {
  testing::ScratchDir dir;
  for (const char* name : {"bad.exr", "bad.png", "bad.bin"}) {
    std::ofstream(dir / name) << "this is not an image";
    try {
      readImage(dir / name);
      FAIL() << "expected InputError for " << name;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(name));
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
    }
  }
}

TEST(ImageIo, TruncatedPngIsInputError) {
  testing::ScratchDir dir;
  writePng(dir / "ok.png", gradient(64, 64, 1.0f));
  const auto size = std::filesystem::file_size(dir / "ok.png");
  std::string bytes(size, '\0');
  std::ifstream(dir / "ok.png", std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(size));
  std::ofstream(dir / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_THROW(readImage(dir / "cut.png"), InputError);
}

TEST(ImageIo, FormatDetectedByMagicWithoutExtension) {
  testing::ScratchDir dir;
  writeExr(dir / "x.exr", gradient(4, 4, 1.0f));
  std::filesystem::copy_file(dir / "x.exr", dir / "noext");
  EXPECT_EQ(detectImageFormat(dir / "noext"), ImageFormat::Exr);
  EXPECT_EQ(readImage(dir / "noext").width, 4u);
}

// Reads `path` with the built-in EXR reader (where it applies) and with OpenEXR alone.
std::pair<Image, Image> readBothWays(const std::filesystem::path& path) {
  Image fast = readImage(path);
  setenv("FGBENCH_EXR_OPENEXR", "1", 1);
  Image reference;
  try {
    reference = readImage(path);
  } catch (...) {
    unsetenv("FGBENCH_EXR_OPENEXR");
    throw;
  }
  unsetenv("FGBENCH_EXR_OPENEXR");
  return {std::move(fast), std::move(reference)};
}

void expectSameBits(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  EXPECT_EQ(a.encoding, b.encoding);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)), 0);  // NaNs included
}

TEST(ImageIo, ExrReadersAgreeBitForBit) {
  testing::ScratchDir dir;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(-2.0f, 70000.0f);
  // Sizes around the 16-line ZIP blocks and the 8-pixel conversion steps; smooth (compressible) and
  // noisy (stored uncompressed) content; half-float specials.
  for (const auto& [w, h] : {std::pair{1u, 1u}, {7u, 3u}, {17u, 16u}, {33u, 37u}, {256u, 40u}}) {
    for (const bool noisy : {false, true}) {
      Image image = gradient(w, h, 40.0f);
      if (noisy) {
        for (float& v : image.rgba) v = value(rng);
      }
      image.rgba[0] = std::numeric_limits<float>::infinity();
      if (image.rgba.size() > 5) image.rgba[5] = std::numeric_limits<float>::quiet_NaN();
      writeExr(dir / "a.exr", image);
      for (const bool vectorised : {true, false}) {  // the AVX2/F16C decoding, and the portable one
        if (!vectorised) setenv("FGBENCH_FLIP_ISA", "baseline", 1);
        const auto [fast, reference] = readBothWays(dir / "a.exr");
        unsetenv("FGBENCH_FLIP_ISA");
        expectSameBits(fast, reference);
        const Image expected = quantizeToHalf(image);
        for (std::size_t i = 6; i < fast.rgba.size(); ++i) ASSERT_EQ(fast.rgba[i], expected.rgba[i]) << w << "x" << h << " value " << i;
      }
    }
  }
}

// An uncompressed file written byte by byte: RGB without alpha plus a float channel the reader
// skips, and a data window that does not start at the origin.
TEST(ImageIo, ExrWithoutAlphaAndWithOffsetWindowReadsLikeOpenExr) {
  testing::ScratchDir dir;
  const int32_t x0 = 3, y0 = -2, w = 11, h = 5;
  std::string bytes;
  auto put = [&bytes](const auto& v) { bytes.append(reinterpret_cast<const char*>(&v), sizeof v); };
  auto attribute = [&](const std::string& name, const std::string& type, const std::string& value) {
    bytes += name + '\0' + type + '\0';
    put(static_cast<int32_t>(value.size()));
    bytes += value;
  };
  auto pack = [](std::initializer_list<int32_t> values) {
    std::string out;
    for (int32_t v : values) out.append(reinterpret_cast<const char*>(&v), sizeof v);
    return out;
  };
  put(uint32_t{20000630});
  put(uint32_t{2});
  std::string channels;
  for (const auto& [name, type] : {std::pair{"B", 1}, {"G", 1}, {"R", 1}, {"Z", 2}}) {
    channels += std::string(name) + '\0' + pack({type}) + std::string(4, '\0') + pack({1, 1});
  }
  attribute("channels", "chlist", channels + '\0');
  attribute("compression", "compression", std::string(1, '\0'));
  attribute("dataWindow", "box2i", pack({x0, y0, x0 + w - 1, y0 + h - 1}));
  attribute("displayWindow", "box2i", pack({0, 0, 15, 15}));
  attribute("lineOrder", "lineOrder", std::string(1, '\0'));
  const float one = 1.0f;
  attribute("pixelAspectRatio", "float", std::string(reinterpret_cast<const char*>(&one), sizeof one));
  attribute("screenWindowCenter", "v2f", std::string(8, '\0'));
  attribute("screenWindowWidth", "float", std::string(reinterpret_cast<const char*>(&one), sizeof one));
  bytes += '\0';
  const std::size_t lineBytes = static_cast<std::size_t>(w) * (3 * 2 + 4);
  const std::size_t tableEnd = bytes.size() + static_cast<std::size_t>(h) * 8;
  for (int32_t y = 0; y < h; ++y) put(static_cast<uint64_t>(tableEnd + static_cast<std::size_t>(y) * (8 + lineBytes)));
  auto halfBits = [](float v) { return Imath::half(v).bits(); };
  for (int32_t y = 0; y < h; ++y) {
    put(y0 + y);
    put(static_cast<int32_t>(lineBytes));
    for (int c = 0; c < 3; ++c) {  // B, G, R
      for (int32_t x = 0; x < w; ++x) put(halfBits(static_cast<float>(100 * c + 10 * y + x) * 0.25f));
    }
    for (int32_t x = 0; x < w; ++x) put(-1.0f);  // Z
  }
  std::ofstream(dir / "rgb.exr", std::ios::binary) << bytes;
  const auto [fast, reference] = readBothWays(dir / "rgb.exr");
  expectSameBits(fast, reference);
  ASSERT_EQ(fast.width, 11u);
  ASSERT_EQ(fast.height, 5u);
  const float* p = &fast.rgba[(2 * 11 + 4) * 4];  // x = 4, y = 2 within the window
  EXPECT_EQ(p[0], (200 + 20 + 4) * 0.25f);  // R
  EXPECT_EQ(p[1], (100 + 20 + 4) * 0.25f);  // G
  EXPECT_EQ(p[2], (0 + 20 + 4) * 0.25f);    // B
  EXPECT_EQ(p[3], 1.0f);                    // no alpha: opaque
}

TEST(ImageIo, TruncatedExrIsInputError) {
  testing::ScratchDir dir;
  writeExr(dir / "ok.exr", gradient(64, 40, 3.0f));
  const auto size = std::filesystem::file_size(dir / "ok.exr");
  std::string bytes(size, '\0');
  std::ifstream(dir / "ok.exr", std::ios::binary).read(bytes.data(), static_cast<std::streamsize>(size));
  std::ofstream(dir / "cut.exr", std::ios::binary) << bytes.substr(0, bytes.size() - 40);
  EXPECT_THROW(readImage(dir / "cut.exr"), InputError);
}

TEST(ImageIo, PairIsReadConcurrentlyAndErrorsNameTheFirstBadFile) {
  testing::ScratchDir dir;
  writeExr(dir / "a.exr", gradient(9, 4, 2.0f));
  writePng(dir / "b.png", gradient(9, 4, 1.0f));
  const auto [a, b] = readImagePair(dir / "a.exr", dir / "b.png");
  EXPECT_EQ(a.encoding, Encoding::Linear);
  EXPECT_EQ(b.encoding, Encoding::Srgb);
  EXPECT_EQ(a.width, 9u);
  try {
    readImagePair(dir / "missing-a.exr", dir / "missing-b.exr");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing-a.exr"));
  }
  try {
    readImagePair(dir / "a.exr", dir / "missing-b.exr");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing-b.exr"));
  }
}

}  // namespace
}  // namespace fgb::harness
