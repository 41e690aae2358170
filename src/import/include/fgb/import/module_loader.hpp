// Model import on demand, for executables that must not link Assimp or OpenImageIO (fgbench).
#pragma once

#include <filesystem>

namespace fgb::import {

// Registers with fgb::scene::loadScene an importer that loads libfgb_import.so on its first call --
// a cooked-cache miss on a model -- and forwards every call to it, so runs that import nothing
// never load the module. If the module cannot be loaded, that call throws an fgb::InputError naming
// the model, the module and dlerror(). Idempotent; call once at start-up.
void enableModelImportOnDemand();

// $FGBENCH_IMPORT_MODULE when set, else libfgb_import.so next to the running executable.
std::filesystem::path importModulePath();

}  // namespace fgb::import
