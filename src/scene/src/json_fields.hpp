// Private: typed access to JSON fields with one-line errors naming the file, field and expectation.
#pragma once

#include <fgb/core/error.hpp>

#include <glm/ext/vector_double3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>

namespace fgb::scene::detail {

class Fields {
 public:
  explicit Fields(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& expected, const nlohmann::json* got) const {
    std::string message = file_ + ": field '" + field + "': expected " + expected;
    if (got) message += ", got " + std::string(got->type_name()) + " " + shorten(got->dump());
    throw InputError(message);
  }

  const nlohmann::json& object(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_object()) fail(field, "an object", &value);
    return value;
  }

  // Rejects keys not in `allowed`, naming the first unknown one and the allowed set.
  void onlyKeys(const nlohmann::json& value, const std::string& field, std::initializer_list<const char*> allowed) const {
    for (const auto& item : value.items()) {
      bool known = false;
      for (const char* key : allowed) known = known || item.key() == key;
      if (!known) {
        std::string list;
        for (const char* key : allowed) list += std::string(list.empty() ? "" : ", ") + key;
        throw InputError(file_ + ": field '" + join(field, item.key()) + "': unknown field (expected one of: " + list + ")");
      }
    }
  }

  double number(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_number()) fail(field, "a number", &value);
    return value.get<double>();
  }
  float positive(const nlohmann::json& value, const std::string& field) const {
    const double v = number(value, field);
    if (!(v > 0.0)) fail(field, "a number > 0", &value);
    return static_cast<float>(v);
  }
  float nonNegative(const nlohmann::json& value, const std::string& field) const {
    const double v = number(value, field);
    if (!(v >= 0.0)) fail(field, "a number >= 0", &value);
    return static_cast<float>(v);
  }
  bool boolean(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_boolean()) fail(field, "true or false", &value);
    return value.get<bool>();
  }
  std::string string(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_string()) fail(field, "a string", &value);
    return value.get<std::string>();
  }
  glm::vec3 vec3(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 3) fail(field, "an array of 3 numbers", &value);
    return {number(value[0], field + "[0]"), number(value[1], field + "[1]"), number(value[2], field + "[2]")};
  }
  // World positions: double, so a scene far from the origin keeps its precision.
  glm::dvec3 dvec3(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 3) fail(field, "an array of 3 numbers", &value);
    return {number(value[0], field + "[0]"), number(value[1], field + "[1]"), number(value[2], field + "[2]")};
  }
  glm::vec4 vec4(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 4) fail(field, "an array of 4 numbers", &value);
    return {number(value[0], field + "[0]"), number(value[1], field + "[1]"), number(value[2], field + "[2]"),
            number(value[3], field + "[3]")};
  }
  uint32_t count(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_number_integer() || value.get<int64_t>() < 0 || value.get<int64_t>() > 0xffffffffLL) {
      fail(field, "a non-negative integer", &value);
    }
    return static_cast<uint32_t>(value.get<int64_t>());
  }

  static std::string join(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
  }
  const std::string& file() const { return file_; }

 private:
  static std::string shorten(std::string text) {
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
  }
  std::string file_;
};

}  // namespace fgb::scene::detail
