// RGBA8 textures with full mip chains, and the fallback that stands in for a missing image.
#pragma once

#include <fgb/scene/scene.hpp>

#include <string>
#include <vector>

namespace fgb::scene {

// Builds a texture from level-0 RGBA8 texels (width * height * 4 bytes) and box-filters its mip
// chain down to 1x1. sRGB textures are filtered in linear space, so mips do not darken.
// Throws fgb::InputError when the size does not match or is zero.
Texture makeTexture(std::string name, uint32_t width, uint32_t height, std::vector<uint8_t> rgba, bool srgb);

// A loud magenta/black checkerboard, so a missing image is visible in every frame.
Texture fallbackTexture(const std::string& missingName, bool srgb);

// Number of levels in a full chain for the given size (1x1 -> 1).
uint32_t mipLevelCount(uint32_t width, uint32_t height);

}  // namespace fgb::scene
