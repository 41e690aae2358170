// Reading JSON inputs (budgets, timings, golden thresholds) with one-line errors that name the file
// and the field: bad input is fgb::InputError, never a crash.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace fgb::harness {

// Parses a JSON file. Missing file or syntax error -> InputError "<file>: ... (line N, column M)".
nlohmann::json readJsonFile(const std::filesystem::path& path);
// The same, keeping objects' keys in file order (nlohmann::json sorts them).
nlohmann::ordered_json readOrderedJsonFile(const std::filesystem::path& path);

// Field access with errors naming file and field path ("passes[2].gpu_ms").
const nlohmann::json& requireField(const nlohmann::json& object, const std::string& key,
                                   const std::filesystem::path& file, const std::string& where = "");
double requireNumber(const nlohmann::json& object, const std::string& key, const std::filesystem::path& file,
                     const std::string& where = "");
std::string requireString(const nlohmann::json& object, const std::string& key, const std::filesystem::path& file,
                          const std::string& where = "");
// Fields that may be absent: the fallback is returned then; a present field of the wrong type throws.
double optionalNumber(const nlohmann::json& object, const std::string& key, double fallback,
                      const std::filesystem::path& file, const std::string& where = "");
std::string optionalString(const nlohmann::json& object, const std::string& key, const std::string& fallback,
                           const std::filesystem::path& file, const std::string& where = "");

// Pretty-printed JSON text with a trailing newline.
std::string dumpJson(const nlohmann::json& value);

}  // namespace fgb::harness
