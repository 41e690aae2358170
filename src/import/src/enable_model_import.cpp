// enableModelImport, apart from the importer itself so that the loadable module, which hands
// importModel to its loader instead, does not pull fgb::scene::loadScene and the cache into it.
#include <fgb/import/model_importer.hpp>

namespace fgb::import {

void enableModelImport() { scene::setModelImporter(importerSignature(), importModel); }

}  // namespace fgb::import
