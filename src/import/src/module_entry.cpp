// The entry point of libfgb_import.so, the loadable import module (see import_module.hpp).
#include <fgb/import/import_module.hpp>
#include <fgb/import/model_importer.hpp>

#include <string>

// The module is built with hidden visibility; this is its one exported symbol.
extern "C" __attribute__((visibility("default"))) const fgb::import::ImportModuleEntry* fgb_import_module_entry() {
  using namespace fgb::import;
  static const std::string signature = importerSignature();
  static const ImportModuleEntry entry{kImportModuleAbiVersion, sizeof(fgb::scene::ImportedModel), signature.c_str(),
                                       &importModel};
  return &entry;
}
