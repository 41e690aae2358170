// Private: deterministic randomness and procedural textures for the generators. No std::
// distributions (their output differs between standard libraries); everything is integer hashing.
#pragma once

#include <fgb/scene/scene.hpp>

#include <cstdint>
#include <string>

namespace fgb::scene::procedural {

class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 0x2545F4914F6CDD1Dull) {}
  uint64_t next() {  // splitmix64
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  float uniform() { return float(next() >> 40) / float(1u << 24); }  // [0, 1)
  float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }

 private:
  uint64_t state_;
};

// Tileable value noise fBm in [0, 1] with `period` cells per texture side.
float fbm(float x, float y, uint32_t period, int octaves, uint32_t seed);

enum class Pattern { Tiles, Marble, Plaster, Sandstone, Fabric, Terracotta, Leaves, Metal };

// Base colour (sRGB, alpha = coverage for Leaves) and a tangent-space normal map (linear) derived
// from the same height field; metallic-roughness (linear, G = roughness, B = metallic).
Texture baseColorTexture(Pattern pattern, uint32_t size, uint32_t seed);
Texture normalTexture(Pattern pattern, uint32_t size, uint32_t seed, float strength);
Texture metallicRoughnessTexture(Pattern pattern, uint32_t size, uint32_t seed);

}  // namespace fgb::scene::procedural
