// Every field of a compiled graph, flattened into numbers (and the cull diagnostic of each node),
// so that two compiles compare with == and a corpus of them hashes into one fingerprint.
#pragma once

#include <cstdint>
#include <fgb/graph/compiled_graph.hpp>
#include <string>
#include <vector>

namespace fgb::graph::test {

struct Flattened {
  std::vector<uint64_t> values;
  std::vector<std::string> diagnostics;
  friend bool operator==(const Flattened&, const Flattened&) = default;
};

Flattened flatten(const FrameGraph& graph, const CompiledGraph& compiled);

// FNV-1a over the values and the diagnostics' characters, each item preceded by its length.
class Fingerprint {
 public:
  void add(uint64_t value);
  void add(const std::string& text);
  void add(const Flattened& flat);
  [[nodiscard]] uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace fgb::graph::test
