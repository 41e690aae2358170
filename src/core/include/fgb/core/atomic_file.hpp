// Atomic file output: content goes to "<path>.tmp.<pid>" and is renamed over <path> only when
// complete, so a crash or error never leaves a half-written file (or a damaged golden).
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string_view>

namespace fgb {

// Writes bytes atomically. Throws std::runtime_error naming the path on failure.
void writeFileAtomic(const std::filesystem::path& path, std::span<const std::byte> bytes);
void writeFileAtomic(const std::filesystem::path& path, std::string_view text);

// For encoders that write to a path themselves (OpenEXR, PNG): `writer` receives the temporary
// path; on success it is renamed to `path`, on exception the temporary is removed and the
// exception propagates.
void writeViaTemporary(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path& temporary)>& writer);

}  // namespace fgb
