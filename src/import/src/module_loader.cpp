// Loads libfgb_import.so on the first model import (see module_loader.hpp).
#include <fgb/import/module_loader.hpp>

#include <fgb/core/error.hpp>
#include <fgb/import/import_module.hpp>
#include <fgb/scene/load.hpp>

#include <dlfcn.h>

#include <cstdlib>
#include <string>
#include <system_error>
#include <utility>

namespace fgb::import {
namespace {

std::string lastDlError() {
  const char* message = dlerror();
  return message ? message : "unknown error";
}

// Owns one dlopen handle.
class SharedLibrary {
 public:
  // Throws InputError with dlerror() when the library or one of its dependencies cannot be loaded.
  explicit SharedLibrary(const std::filesystem::path& path)
      // RTLD_NOW: a missing symbol fails here, with a message, not later in the middle of an import.
      // RTLD_NODELETE: Assimp and OpenImageIO keep worker threads and exit handlers, so the module
      // must stay mapped until the process ends, even after this handle is closed.
      : handle_(dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE)) {
    if (!handle_) throw InputError("cannot load " + path.string() + ": " + lastDlError());
  }
  ~SharedLibrary() {
    if (handle_) dlclose(handle_);
  }
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;

  void* symbol(const char* name) const { return dlsym(handle_, name); }

 private:
  void* handle_;
};

// The loaded module and its entry table, checked to come from this build.
class ImportModule {
 public:
  explicit ImportModule(const std::filesystem::path& path) : library_(path), entry_(loadEntry(path)) {}

  scene::ImportedModel importModel(const std::filesystem::path& model) const { return entry_.importModel(model); }

 private:
  ImportModuleEntry loadEntry(const std::filesystem::path& path) const {
    using EntryPoint = const ImportModuleEntry* (*)();
    auto* entryPoint = reinterpret_cast<EntryPoint>(library_.symbol(kImportModuleEntryPoint));
    if (!entryPoint) throw InputError(path.string() + " is not an fgbench import module: " + lastDlError());
    const ImportModuleEntry* entry = entryPoint();
    if (!entry || entry->abiVersion != kImportModuleAbiVersion ||
        entry->importedModelSize != sizeof(scene::ImportedModel) || !entry->signature || !entry->importModel) {
      throw InputError(path.string() + " is from another fgbench build; rebuild it (target fgb_import_module)");
    }
    if (entry->signature != importerSignature()) {
      // The signature is in the cache keys fgbench already formed; a different one would store
      // this importer's output under another importer's keys.
      throw InputError(path.string() + " has importer signature " + entry->signature + ", fgbench expects " +
                       importerSignature() + "; rebuild it (target fgb_import_module)");
    }
    return *entry;
  }

  SharedLibrary library_;
  ImportModuleEntry entry_;
};

// Loaded once per process, on first use; a failed load throws and is retried by the next import.
const ImportModule& importModule() {
  static const ImportModule module(importModulePath());
  return module;
}

scene::ImportedModel importOnDemand(const std::filesystem::path& model) {
  const ImportModule* module = nullptr;
  try {
    module = &importModule();
  } catch (const InputError& e) {
    throw InputError(model.string() + ": model import unavailable: " + e.what());
  }
  return module->importModel(model);
}

}  // namespace

std::filesystem::path importModulePath() {
  if (const char* override = std::getenv("FGBENCH_IMPORT_MODULE"); override && *override) return override;
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  // Without /proc, the bare name leaves the search to dlopen (LD_LIBRARY_PATH, RUNPATH, ld.so.cache).
  if (error) return FGB_IMPORT_MODULE_FILE_NAME;
  return executable.parent_path() / FGB_IMPORT_MODULE_FILE_NAME;
}

void enableModelImportOnDemand() { scene::setModelImporter(importerSignature(), importOnDemand); }

}  // namespace fgb::import
