// Image files: OpenEXR (half-float RGBA, linear) and PNG (8-bit sRGB) — nothing else, so the GPU-side
// binary stays small. Reading a missing, unreadable or corrupt file throws fgb::InputError with one
// line naming the file; writing is atomic (temporary + rename).
#pragma once

#include <fgb/harness/image/image.hpp>

#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

namespace fgb::harness {

enum class ImageFormat { Exr, Png };

// By extension (.exr / .png, any case); otherwise by the file's magic bytes. Throws InputError.
ImageFormat detectImageFormat(const std::filesystem::path& path);

Image readImage(const std::filesystem::path& path);
// Both images, decoded concurrently; errors as reading first `a` then `b` would report them.
std::pair<Image, Image> readImagePair(const std::filesystem::path& a, const std::filesystem::path& b);
Image readExr(const std::filesystem::path& path);  // encoding Linear
Image readPng(const std::filesystem::path& path);  // encoding Srgb, values in [0, 1]

// Half-float RGBA, ZIP compression. Expects a linear image.
void writeExr(const std::filesystem::path& path, const Image& linear);
// 32-bit float, the first `channels` (1-4) of R, G, B, A, ZIP compression: exact values (depth,
// ids). readExr fills missing colour channels with 0 and alpha with 1.
void writeExrFloat(const std::filesystem::path& path, const Image& linear, int channels);
// 8-bit RGB. Linear images are sRGB-encoded (clamped); sRGB images are stored as they are.
void writePng(const std::filesystem::path& path, const Image& image);
// The PNG file writePng would write, in memory (for data: URIs in single-file reports).
std::vector<uint8_t> encodePng(const Image& image);

}  // namespace fgb::harness
