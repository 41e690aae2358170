#include <fgb/core/atomic_file.hpp>

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace fgb {
namespace {

std::filesystem::path temporaryFor(const std::filesystem::path& path) {
  return path.string() + ".tmp." + std::to_string(::getpid());
}

}  // namespace

void writeViaTemporary(const std::filesystem::path& path,
                       const std::function<void(const std::filesystem::path& temporary)>& writer) {
  const auto temporary = temporaryFor(path);
  try {
    writer(temporary);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    throw std::runtime_error(path.string() + ": cannot replace file: " + ec.message());
  }
}

void writeFileAtomic(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  writeViaTemporary(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(temporary.string() + ": cannot open for writing");
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw std::runtime_error(temporary.string() + ": write failed");
  });
}

void writeFileAtomic(const std::filesystem::path& path, std::string_view text) {
  writeFileAtomic(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace fgb
