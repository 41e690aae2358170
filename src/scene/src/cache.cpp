// Cooked cache entries: header + checksummed payload, written atomically.
#include <fgb/scene/cache.hpp>

#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/scene/cook.hpp>

#include "serialize.hpp"

#include <xxhash.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace fgb::scene {
namespace {

constexpr char kMagic[8] = {'F', 'G', 'B', 'C', 'O', 'O', 'K', '\0'};
constexpr uint32_t kFormatVersion = 1;

struct EntryHeader {
  char magic[8];
  uint32_t formatVersion;
  uint32_t cookerVersion;
  uint64_t payloadSize;
  uint64_t payloadHash;  // XXH3-64 of the payload
};
static_assert(sizeof(EntryHeader) == 32);

std::optional<std::vector<std::byte>> readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) return std::nullopt;
  in.seekg(0, std::ios::beg);
  std::vector<std::byte> bytes(static_cast<size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) return std::nullopt;
  return bytes;
}

std::string hex64(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Empty string when every dependency still has the recorded content; else what changed.
std::string staleDependency(const std::vector<CacheDependency>& dependencies, const std::filesystem::path& baseDir) {
  for (const CacheDependency& recorded : dependencies) {
    const auto now = describeDependency(baseDir, recorded.path);
    if (!now) return "dependency '" + recorded.path + "' is gone";
    if (now->size != recorded.size || now->hash != recorded.hash) return "dependency '" + recorded.path + "' changed";
  }
  return {};
}

}  // namespace

CacheKey::CacheKey() : state_(XXH3_createState()) { XXH3_128bits_reset(static_cast<XXH3_state_t*>(state_)); }
CacheKey::~CacheKey() { XXH3_freeState(static_cast<XXH3_state_t*>(state_)); }

CacheKey& CacheKey::add(std::span<const std::byte> bytes) {
  // Length-prefix every field so ("ab","c") and ("a","bc") give different keys.
  const uint64_t size = bytes.size();
  XXH3_128bits_update(static_cast<XXH3_state_t*>(state_), &size, sizeof size);
  XXH3_128bits_update(static_cast<XXH3_state_t*>(state_), bytes.data(), bytes.size());
  return *this;
}

CacheKey& CacheKey::add(std::string_view text) { return add(std::as_bytes(std::span(text.data(), text.size()))); }

CacheKey& CacheKey::addFile(const std::filesystem::path& path) {
  const auto bytes = readWholeFile(path);
  if (!bytes) throw InputError(path.string() + ": cannot read file");
  return add(*bytes);
}

std::string CacheKey::finish() const {
  const XXH128_hash_t hash = XXH3_128bits_digest(static_cast<XXH3_state_t*>(state_));
  return hex64(hash.high64) + hex64(hash.low64);
}

std::optional<CacheDependency> describeDependency(const std::filesystem::path& baseDir, const std::string& path) {
  const std::filesystem::path full = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : baseDir / path;
  const auto bytes = readWholeFile(full);
  if (!bytes) return std::nullopt;
  return CacheDependency{path, bytes->size(), XXH3_64bits(bytes->data(), bytes->size())};
}

CookedCache::CookedCache(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path CookedCache::defaultDirectory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "fgbench";
  if (const char* home = std::getenv("HOME"); home && *home) return std::filesystem::path(home) / ".cache" / "fgbench";
  return std::filesystem::current_path() / ".fgbench-cache";
}

std::filesystem::path CookedCache::entryPath(const std::string& key) const {
  return directory_ / key.substr(0, 2) / (key + ".fgbcooked");
}

CacheLookup CookedCache::load(const std::string& key, const std::filesystem::path& baseDir) const {
  const auto start = std::chrono::steady_clock::now();
  CacheLookup lookup;
  const std::filesystem::path path = entryPath(key);
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return lookup;
  const auto bytes = readWholeFile(path);
  auto corrupt = [&](const std::string& why) {
    lookup.status = CacheStatus::Corrupt;
    lookup.reason = path.string() + ": " + why;
    return lookup;
  };
  if (!bytes) return corrupt("unreadable");
  if (bytes->size() < sizeof(EntryHeader)) return corrupt("truncated header");
  EntryHeader header;
  std::memcpy(&header, bytes->data(), sizeof header);
  if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0) return corrupt("not a cooked entry");
  if (header.formatVersion != kFormatVersion || header.cookerVersion != kCookerVersion) {
    return corrupt("written by another cooker version");
  }
  const std::byte* payload = bytes->data() + sizeof header;
  const size_t payloadSize = bytes->size() - sizeof header;
  if (header.payloadSize != payloadSize) return corrupt("truncated (size mismatch)");
  if (XXH3_64bits(payload, payloadSize) != header.payloadHash) return corrupt("checksum mismatch");
  try {
    detail::Reader reader(payload, payloadSize);
    std::vector<CacheDependency> dependencies;
    const auto count = reader.pod<uint64_t>();
    for (uint64_t i = 0; i < count; ++i) {
      CacheDependency dependency;
      dependency.path = reader.string();
      dependency.size = reader.pod<uint64_t>();
      dependency.hash = reader.pod<uint64_t>();
      dependencies.push_back(std::move(dependency));
    }
    if (std::string why = staleDependency(dependencies, baseDir); !why.empty()) {
      lookup.status = CacheStatus::Stale;
      lookup.reason = why;
      return lookup;
    }
    lookup.scene = detail::readScene(reader);
    if (!reader.atEnd()) return corrupt("trailing bytes");
  } catch (const detail::CorruptData& e) {
    return corrupt(e.what());
  }
  lookup.status = CacheStatus::Hit;
  lookup.readMs = millisecondsSince(start);
  return lookup;
}

void CookedCache::store(const std::string& key, const Scene& scene,
                        const std::vector<CacheDependency>& dependencies) const {
  std::vector<std::byte> bytes;
  // One allocation for the whole entry: the big arrays dominate, the rest fits in the slack.
  size_t estimate = sizeof(EntryHeader) + (1u << 20) + scene.positions.size() * 48 + scene.indices.size() * 4;
  for (const Texture& texture : scene.textures) estimate += texture.data.size() + texture.name.size() + 64;
  bytes.reserve(estimate);
  bytes.resize(sizeof(EntryHeader));
  {
    detail::VectorSink sink{bytes};
    detail::Writer<detail::VectorSink> writer(sink);
    writer.pod(static_cast<uint64_t>(dependencies.size()));
    for (const CacheDependency& dependency : dependencies) {
      writer.string(dependency.path);
      writer.pod(dependency.size);
      writer.pod(dependency.hash);
    }
    detail::writeScene(writer, scene);
  }
  EntryHeader header;
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.formatVersion = kFormatVersion;
  header.cookerVersion = kCookerVersion;
  header.payloadSize = bytes.size() - sizeof header;
  header.payloadHash = XXH3_64bits(bytes.data() + sizeof header, header.payloadSize);
  std::memcpy(bytes.data(), &header, sizeof header);
  const std::filesystem::path path = entryPath(key);
  std::filesystem::create_directories(path.parent_path());
  writeFileAtomic(path, bytes);
}

const char* toString(CacheStatus status) {
  switch (status) {
    case CacheStatus::Hit: return "hit";
    case CacheStatus::Missing: return "miss";
    case CacheStatus::Corrupt: return "corrupt";
    case CacheStatus::Stale: return "stale";
  }
  return "?";
}

}  // namespace fgb::scene
