// Fast path for the common EXR layout, used by readExr before OpenEXR.
// Single-part scan-line files, uncompressed or ZIP/ZIPS, all channels at full resolution: what
// writeExr, the renderer and most tools produce. OpenEXR 3.1 inflates with zlib, whose copy loop
// for long matches made decoding a 4K pair cost as much as the whole `oiiotool --diff`; libdeflate
// (where the system has it: loaded at run time, so it is no build dependency) inflates the same
// blocks 3-10x faster. Everything else, and any file this reader does not fully understand, goes
// through OpenEXR, which also produces the error messages for broken files.
#pragma once

#include <fgb/harness/image/image.hpp>

#include <filesystem>
#include <optional>

namespace fgb::harness::detail {

// The image, or nullopt when this reader does not handle the file (layout, compression, no
// libdeflate, FGBENCH_EXR_OPENEXR set, or anything it does not fully understand): then OpenEXR reads
// it and reports errors.
std::optional<Image> readExrFast(const std::filesystem::path& path);

}  // namespace fgb::harness::detail
