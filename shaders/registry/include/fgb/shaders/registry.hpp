// Embedded SPIR-V of every shader under shaders/, compiled at build time (Vulkan 1.3 target).
// Shaders are named by their path relative to shaders/, e.g. "proof/scene.vert".
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::shaders {

// The SPIR-V words of a shader. Throws fgb::InputError naming the shader when it does not exist.
std::span<const uint32_t> spirv(std::string_view path);

// True when a shader with this path was embedded.
bool contains(std::string_view path);

// The embedded name of a shader's variant: the source compiled once more with a preprocessor
// definition (the shader_variants list in shaders/CMakeLists.txt), e.g. "a/b.comp:image".
std::string variantPath(std::string_view path, std::string_view variant);

// Every embedded shader path, sorted.
std::vector<std::string_view> names();

}  // namespace fgb::shaders
