// Private: image decoding with OpenImageIO into RGBA8 (grey -> RGB, missing alpha -> 255).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fgb::import {

struct DecodedImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba;
};

// nullopt (with `error` set) when the file is missing or cannot be decoded.
std::optional<DecodedImage> decodeImageFile(const std::filesystem::path& path, std::string& error);
// Decodes an in-memory file (e.g. an embedded PNG); `formatHint` is its extension ("png", "jpg").
std::optional<DecodedImage> decodeImageMemory(std::span<const uint8_t> bytes, const std::string& formatHint,
                                              std::string& error);

}  // namespace fgb::import
