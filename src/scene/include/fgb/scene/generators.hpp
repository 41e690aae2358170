// Procedural scene generators, deterministic by seed (same parameters -> byte-identical scene).
//
//   atrium            Sponza-like two-storey courtyard: 115 instances, ~3.78 M triangles, 28 point
//                     lights, one brazier emitter, procedural textures. Params: scale (geometry
//                     density, default 1), seed (1), texture_size (512).
//   city              Occluder-rich street grid (issue 26): blocks x blocks blocks of 4-15 storey
//                     buildings with detailed facades, a street lamp (point light) every half block
//                     side. Params: blocks (9: 6.0 M triangles, 360 lights; 2 for CI), seed (1),
//                     texture_size (512).
//   showcase          Small feature scenes: a floor and a grid of objects. Params: objects (9),
//                     alpha ("opaque"|"mask"|"blend"), floor (true), lights (4), emissive (false),
//                     sun (true), seed (1).
//   stress-far        The atrium placed `offset` (1e6) metres from the origin.
//   stress-depth      The atrium seen with near = 1e-4, far = 1e5.
//   stress-lights     The atrium with `count` (64) lights, intensities log-spaced 1e-6 .. 1e6.
//   stress-triangles  Slivers, degenerate, zero-area and huge triangles (the last two kinds are
//                     removed and counted by the repair pass). Params: count (2000), seed.
//   stress-nan        A showcase whose vertex data is laced with NaN/Inf (fraction 0.01), repaired
//                     and counted. Params: fraction, seed.
// The atrium-based stress generators accept the atrium's params too.
#pragma once

#include <fgb/scene/knobs.hpp>
#include <fgb/scene/scene.hpp>
#include <fgb/scene/scene_file.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fgb::scene {

const std::vector<std::string>& generatorNames();

// Defaults, then the scene file's params, then --set knobs (atrium.*, city.*, stress.*); validated.
// The result is canonical (sorted keys, numbers) and is what the cache key hashes.
// InputError names `where` (the scene file) and the offending field.
nlohmann::json resolveGeneratorParams(const GeneratorRef& generator, const Knobs& knobs, const std::string& where);

// Generates an uncooked scene from resolved params. Meshes are repaired; cookScene() finishes it.
Scene generate(const std::string& type, const nlohmann::json& resolvedParams);

}  // namespace fgb::scene
