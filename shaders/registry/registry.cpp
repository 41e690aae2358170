#include <fgb/core/error.hpp>
#include <fgb/shaders/registry.hpp>

#include <algorithm>
#include <string>

#include "shader_table.hpp"

namespace fgb::shaders {
namespace {

const detail::ShaderEntry* find(std::string_view path) {
  const auto& table = detail::kShaderTable;
  const auto it = std::find_if(table.begin(), table.end(), [&](const auto& e) { return e.path == path; });
  return it == table.end() ? nullptr : &*it;
}

}  // namespace

std::span<const uint32_t> spirv(std::string_view path) {
  if (const auto* entry = find(path)) return entry->words;
  throw InputError("shader '" + std::string(path) + "' is not embedded (no shaders/" + std::string(path) +
                   " at build time)");
}

std::string variantPath(std::string_view path, std::string_view variant) {
  return std::string(path).append(":").append(variant);
}

bool contains(std::string_view path) { return find(path) != nullptr; }

std::vector<std::string_view> names() {
  std::vector<std::string_view> result;
  for (const auto& entry : detail::kShaderTable) result.push_back(entry.path);
  std::sort(result.begin(), result.end());
  return result;
}

}  // namespace fgb::shaders
