// Model import through Assimp (glTF 2.0 .gltf/.glb, OBJ/MTL, FBX, Collada and everything else
// Assimp reads) with textures decoded by OpenImageIO. Produces an uncooked fgb::scene::Scene:
// meshes repaired and counted by fgb::scene::repairMesh, one instance per (node, mesh), glTF
// metallic-roughness materials (Phong materials converted), point lights, the first camera.
//
// Hostile input never crashes: a missing texture becomes the fallback checkerboard plus one warning
// naming it; an index out of range, a truncated file or an unsupported format is an
// fgb::InputError naming the file (and the mesh).
#pragma once

#include <fgb/import/import_module.hpp>  // importerSignature()
#include <fgb/scene/load.hpp>

#include <filesystem>
#include <string>

namespace fgb::import {

fgb::scene::ImportedModel importModel(const std::filesystem::path& model);

// Registers importModel with fgb::scene::loadScene (idempotent). Call once at start-up in every
// executable that links fgb_import and should import models on a cache miss; fgbench, which does
// not, uses enableModelImportOnDemand() (module_loader.hpp) instead.
void enableModelImport();

}  // namespace fgb::import
