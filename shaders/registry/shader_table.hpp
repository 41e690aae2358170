// Internal: the generated table of embedded shaders (see shader_table.cpp.in).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace fgb::shaders::detail {

struct ShaderEntry {
  std::string_view path;
  std::span<const uint32_t> words;
};

extern const std::span<const ShaderEntry> kShaderTable;

}  // namespace fgb::shaders::detail
