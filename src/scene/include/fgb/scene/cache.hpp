// The content-addressed cooked-asset cache. An entry is keyed by the bytes of its input, the
// settings that shaped it and kCookerVersion; it stores the cooked Scene plus the other files the
// input pulled in (textures, .bin, .mtl) with their hashes, so editing one of those invalidates it.
// Entries are written atomically and checksummed; a truncated or corrupt entry is reported as such
// and rebuilt by the loader. Reading needs neither Assimp nor OpenImageIO.
#pragma once

#include <fgb/scene/scene.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fgb::scene {

// Builds a cache key: feed everything that determines the cooked output, then finish().
class CacheKey {
 public:
  CacheKey();
  ~CacheKey();
  CacheKey(const CacheKey&) = delete;
  CacheKey& operator=(const CacheKey&) = delete;
  CacheKey& add(std::span<const std::byte> bytes);
  CacheKey& add(std::string_view text);
  CacheKey& addFile(const std::filesystem::path& path);  // the file's bytes; InputError if unreadable
  std::string finish() const;  // 32 hex digits (XXH3-128)

 private:
  void* state_;
};

struct CacheDependency {
  std::string path;  // relative to the input's directory (or absolute)
  uint64_t size = 0;
  uint64_t hash = 0;  // XXH3-64 of the content
};

// Hashes a file for a dependency record; nullopt when it cannot be read.
std::optional<CacheDependency> describeDependency(const std::filesystem::path& baseDir, const std::string& path);

enum class CacheStatus { Hit, Missing, Corrupt, Stale };

struct CacheLookup {
  CacheStatus status = CacheStatus::Missing;
  std::optional<Scene> scene;  // set on Hit
  std::string reason;          // why not a hit (Corrupt/Stale)
  double readMs = 0.0;         // read + checksum + decode
};

class CookedCache {
 public:
  explicit CookedCache(std::filesystem::path directory);

  // $XDG_CACHE_HOME/fgbench, else $HOME/.cache/fgbench, else ./.fgbench-cache.
  static std::filesystem::path defaultDirectory();

  const std::filesystem::path& directory() const { return directory_; }
  std::filesystem::path entryPath(const std::string& key) const;

  // Loads an entry; dependencies are re-hashed relative to `baseDir`.
  CacheLookup load(const std::string& key, const std::filesystem::path& baseDir) const;
  // Stores an entry atomically (creating the directory). Throws std::runtime_error on I/O failure.
  void store(const std::string& key, const Scene& scene, const std::vector<CacheDependency>& dependencies) const;

 private:
  std::filesystem::path directory_;
};

const char* toString(CacheStatus status);

}  // namespace fgb::scene
