#include <fgb/harness/base/json_io.hpp>

#include <fgb/core/error.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace fgb::harness {
namespace {

std::string fieldName(const std::string& where, const std::string& key) {
  return where.empty() ? key : where + "." + key;
}

// "line L, column C" of a byte offset, for parse errors.
std::string lineAndColumn(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(byte, text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::string oneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

}  // namespace

namespace {

template <typename Json>
Json parseJsonFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string() + ": no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based and points just past the offending character.
    const std::size_t at = e.byte > 0 ? e.byte - 1 : 0;
    std::string reason = oneLine(e.what());
    if (const auto colon = reason.rfind(": "); colon != std::string::npos) reason = reason.substr(colon + 2);
    throw InputError(path.string() + ": invalid JSON at " + lineAndColumn(text, at) + ": " + reason);
  }
}

}  // namespace

nlohmann::json readJsonFile(const std::filesystem::path& path) { return parseJsonFile<nlohmann::json>(path); }

nlohmann::ordered_json readOrderedJsonFile(const std::filesystem::path& path) {
  return parseJsonFile<nlohmann::ordered_json>(path);
}

const nlohmann::json& requireField(const nlohmann::json& object, const std::string& key,
                                   const std::filesystem::path& file, const std::string& where) {
  if (!object.is_object()) {
    throw InputError(file.string() + ": " + (where.empty() ? std::string("top level") : where) + " must be a JSON object");
  }
  const auto it = object.find(key);
  if (it == object.end()) throw InputError(file.string() + ": missing field '" + fieldName(where, key) + "'");
  return *it;
}

double requireNumber(const nlohmann::json& object, const std::string& key, const std::filesystem::path& file,
                     const std::string& where) {
  const auto& value = requireField(object, key, file, where);
  if (!value.is_number()) throw InputError(file.string() + ": field '" + fieldName(where, key) + "' must be a number");
  return value.get<double>();
}

std::string requireString(const nlohmann::json& object, const std::string& key, const std::filesystem::path& file,
                          const std::string& where) {
  const auto& value = requireField(object, key, file, where);
  if (!value.is_string()) throw InputError(file.string() + ": field '" + fieldName(where, key) + "' must be a string");
  return value.get<std::string>();
}

double optionalNumber(const nlohmann::json& object, const std::string& key, double fallback,
                      const std::filesystem::path& file, const std::string& where) {
  if (!object.is_object() || !object.contains(key)) return fallback;
  return requireNumber(object, key, file, where);
}

std::string optionalString(const nlohmann::json& object, const std::string& key, const std::string& fallback,
                           const std::filesystem::path& file, const std::string& where) {
  if (!object.is_object() || !object.contains(key)) return fallback;
  return requireString(object, key, file, where);
}

std::string dumpJson(const nlohmann::json& value) { return value.dump(2) + "\n"; }

}  // namespace fgb::harness
