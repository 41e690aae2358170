#include <fgb/core/error.hpp>
#include <fgb/harness/image_io.hpp>

#include "test_util.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

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

}  // namespace
}  // namespace fgb::harness
