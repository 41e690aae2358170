// Scene files (JSON): a model, a generator, or both, plus camera, lights, emitters and post
// settings. The schema is documented in scenes/README.md. Every error names the file, the field
// and what was expected, on one line (fgb::InputError).
#pragma once

#include <fgb/scene/scene.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fgb::scene {

struct ModelRef {
  std::filesystem::path file;  // resolved against the scene file's directory
  glm::dmat4 placement{1.0};
  std::string field;           // e.g. "models[1]", for messages
};

struct GeneratorRef {
  std::string type;            // "atrium", "showcase", "stress-far", ...
  nlohmann::json params;       // the generator object without "type" (validated by the generator)
};

struct SceneDescription {
  std::filesystem::path path;
  std::string name;                     // "name", else the file's stem
  std::optional<GeneratorRef> generator;
  std::vector<ModelRef> models;
  nlohmann::json camera;                // partial overrides of the source's camera (object or null)
  std::vector<PointLight> lights;       // added to the generator's/models' lights
  std::optional<DirectionalLight> sun;  // replaces the source's
  std::vector<Emitter> emitters;        // added
  nlohmann::json post;                  // partial overrides (object or null)
  nlohmann::json renderer;              // sections the scene side does not read: render, budget, ...
};

// Reads and validates a scene file. InputError "<file>: <field>: expected ..." on any problem.
SceneDescription parseSceneFile(const std::filesystem::path& path);
// Same, from text already in memory (path used for messages and relative paths).
SceneDescription parseSceneText(const std::string& text, const std::filesystem::path& path);

// Applies a partial camera object ({"position","target","up","fov_deg","near","far"}).
void applyCameraOverrides(Camera& camera, const nlohmann::json& overrides, const std::string& where);
// Applies a partial post object ({"exposure", "bloom": {"enabled","threshold","knee","intensity","radius"}}).
void applyPostOverrides(PostSettings& post, const nlohmann::json& overrides, const std::string& where);

}  // namespace fgb::scene
