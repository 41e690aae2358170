// The loadable import module, libfgb_import.so: fgb_import (Assimp + OpenImageIO) built as a
// shared object with one extern "C" entry point. fgbench links neither library -- their ~260
// shared libraries would cost ~0.2 s of dynamic linking at every start, for every verb -- and
// loads the module only when a model actually has to be imported (see module_loader.hpp).
//
// This header is Assimp-free: fgbench includes it to form model cache keys without the module.
#pragma once

#include <fgb/scene/load.hpp>

#include <cstddef>
#include <filesystem>
#include <string>

namespace fgb::import {

// Assimp post-processing flags of the import: aiProcess_Triangulate | aiProcess_JoinIdenticalVertices
// | aiProcess_SortByPType | aiProcess_FlipUVs (assimp_import.cpp checks the value). Spelled out here
// because they are part of the cache key, which must be known before the module is loaded.
inline constexpr unsigned kImportPostProcessFlags = 0x0080800Au;

// Identifies the importer and its settings in cache keys; bump when output changes.
inline std::string importerSignature() {
  return "assimp-" + std::to_string(kImportPostProcessFlags) + "-oiio-rgba8-v1";
}

// What the module's entry point returns. Scene types cross the boundary as C++ objects, which is
// sound only for a module from the same build: the loader checks abiVersion, the type size and the
// signature, so a stale module is an error rather than a crash.
inline constexpr unsigned kImportModuleAbiVersion = 1;
inline constexpr char kImportModuleEntryPoint[] = "fgb_import_module_entry";

struct ImportModuleEntry {
  unsigned abiVersion = 0;
  std::size_t importedModelSize = 0;  // sizeof(scene::ImportedModel) as the module was compiled
  const char* signature = nullptr;    // the module's importerSignature()
  scene::ImportedModel (*importModel)(const std::filesystem::path& model) = nullptr;
};

}  // namespace fgb::import

// Defined by libfgb_import.so; looked up by name (kImportModuleEntryPoint), never linked against.
extern "C" const fgb::import::ImportModuleEntry* fgb_import_module_entry();
