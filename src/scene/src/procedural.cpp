// Procedural textures: tileable value-noise height fields shaped per material.
#include "procedural.hpp"

#include <fgb/scene/texture.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fgb::scene::procedural {
namespace {

uint32_t hash2(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return h;
}

float lattice(int x, int y, uint32_t period, uint32_t seed) {
  const auto wrap = [period](int v) { return static_cast<uint32_t>(((v % int(period)) + int(period)) % int(period)); };
  return float(hash2(wrap(x), wrap(y), seed) & 0xffffffu) / float(0xffffffu);
}

float valueNoise(float x, float y, uint32_t period, uint32_t seed) {
  const float fx = std::floor(x), fy = std::floor(y);
  const int ix = int(fx), iy = int(fy);
  float tx = x - fx, ty = y - fy;
  tx = tx * tx * (3 - 2 * tx);
  ty = ty * ty * (3 - 2 * ty);
  const float a = lattice(ix, iy, period, seed), b = lattice(ix + 1, iy, period, seed);
  const float c = lattice(ix, iy + 1, period, seed), d = lattice(ix + 1, iy + 1, period, seed);
  return glm::mix(glm::mix(a, b, tx), glm::mix(c, d, tx), ty);
}

// Height in [0, 1] at texture coordinate (u, v) in [0, 1)^2 for a pattern.
float height(Pattern pattern, float u, float v, uint32_t seed) {
  switch (pattern) {
    case Pattern::Tiles: {
      const float gu = std::fmod(u * 8.0f, 1.0f), gv = std::fmod(v * 8.0f, 1.0f);
      const float grout = std::min(std::min(gu, 1 - gu), std::min(gv, 1 - gv));
      return (grout < 0.03f ? 0.0f : 0.8f) + 0.2f * fbm(u, v, 16, 4, seed);
    }
    case Pattern::Marble: {
      const float n = fbm(u, v, 4, 5, seed);
      return 0.5f + 0.5f * std::sin((u * 6.0f + n * 4.0f) * 3.14159265f);
    }
    case Pattern::Plaster: return fbm(u, v, 32, 5, seed);
    case Pattern::Sandstone: {
      const float rows = std::fmod(v * 6.0f, 1.0f);
      return (rows < 0.05f ? 0.1f : 0.7f) + 0.3f * fbm(u, v, 24, 4, seed);
    }
    case Pattern::Fabric: {
      const float weave = 0.5f + 0.25f * (std::sin(u * 512.0f) + std::sin(v * 512.0f));
      return 0.7f * weave + 0.3f * fbm(u, v, 8, 3, seed);
    }
    case Pattern::Terracotta: return fbm(u, v, 16, 4, seed);
    case Pattern::Leaves: return fbm(u, v, 6, 3, seed);
    case Pattern::Metal: return fbm(u, v, 64, 3, seed);
  }
  return 0.0f;
}

glm::vec3 palette(Pattern pattern, float h) {
  switch (pattern) {
    case Pattern::Tiles: return glm::mix(glm::vec3(0.25f, 0.22f, 0.2f), glm::vec3(0.62f, 0.58f, 0.52f), h);
    case Pattern::Marble: return glm::mix(glm::vec3(0.55f, 0.53f, 0.5f), glm::vec3(0.9f, 0.88f, 0.85f), h);
    case Pattern::Plaster: return glm::mix(glm::vec3(0.6f, 0.52f, 0.42f), glm::vec3(0.8f, 0.72f, 0.6f), h);
    case Pattern::Sandstone: return glm::mix(glm::vec3(0.45f, 0.38f, 0.28f), glm::vec3(0.78f, 0.68f, 0.5f), h);
    case Pattern::Fabric: return glm::vec3(0.55f + 0.45f * h);  // greyscale, tinted by the factor
    case Pattern::Terracotta: return glm::mix(glm::vec3(0.45f, 0.18f, 0.08f), glm::vec3(0.72f, 0.35f, 0.18f), h);
    case Pattern::Leaves: return glm::mix(glm::vec3(0.08f, 0.22f, 0.05f), glm::vec3(0.25f, 0.5f, 0.12f), h);
    case Pattern::Metal: return glm::mix(glm::vec3(0.35f, 0.33f, 0.3f), glm::vec3(0.6f, 0.58f, 0.55f), h);
  }
  return glm::vec3(1.0f);
}

uint8_t toByte(float value) { return static_cast<uint8_t>(std::clamp(value * 255.0f + 0.5f, 0.0f, 255.0f)); }

template <typename Texel>
Texture render(const std::string& name, uint32_t size, bool srgb, Texel&& texel) {
  std::vector<uint8_t> rgba(size_t(size) * size * 4);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const glm::vec4 c = texel((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
      uint8_t* out = &rgba[(size_t(y) * size + x) * 4];
      for (int k = 0; k < 4; ++k) out[k] = toByte(c[k]);
    }
  }
  return makeTexture(name, size, size, std::move(rgba), srgb);
}

const char* nameOf(Pattern pattern) {
  constexpr const char* names[] = {"tiles", "marble", "plaster", "sandstone", "fabric", "terracotta", "leaves", "metal"};
  return names[static_cast<int>(pattern)];
}

}  // namespace

float fbm(float x, float y, uint32_t period, int octaves, uint32_t seed) {
  float sum = 0.0f, amplitude = 0.5f, total = 0.0f;
  for (int octave = 0; octave < octaves; ++octave) {
    sum += amplitude * valueNoise(x * float(period), y * float(period), period, seed + uint32_t(octave));
    total += amplitude;
    amplitude *= 0.5f;
    period *= 2;
  }
  return sum / total;
}

Texture baseColorTexture(Pattern pattern, uint32_t size, uint32_t seed) {
  return render(std::string("generated:") + nameOf(pattern) + "-base", size, true, [&](float u, float v) {
    const float h = height(pattern, u, v, seed);
    float alpha = 1.0f;
    if (pattern == Pattern::Leaves) {
      // Leaf-shaped coverage: ellipses on a 4x4 grid, cut out with the alpha mask.
      const float cu = std::fmod(u * 4.0f, 1.0f) - 0.5f, cv = std::fmod(v * 4.0f, 1.0f) - 0.5f;
      alpha = (cu * cu * 9.0f + cv * cv * 4.5f) < 1.0f ? 1.0f : 0.0f;
    }
    return glm::vec4(palette(pattern, h), alpha);
  });
}

Texture normalTexture(Pattern pattern, uint32_t size, uint32_t seed, float strength) {
  const float step = 1.0f / float(size);
  return render(std::string("generated:") + nameOf(pattern) + "-normal", size, false, [&](float u, float v) {
    const auto wrapped = [](float t) { return t - std::floor(t); };
    const float dx = height(pattern, wrapped(u + step), v, seed) - height(pattern, wrapped(u - step), v, seed);
    const float dy = height(pattern, u, wrapped(v + step), seed) - height(pattern, u, wrapped(v - step), seed);
    const glm::vec3 n = glm::normalize(glm::vec3(-dx * strength, -dy * strength, 1.0f));
    return glm::vec4(n * 0.5f + 0.5f, 1.0f);
  });
}

Texture metallicRoughnessTexture(Pattern pattern, uint32_t size, uint32_t seed) {
  return render(std::string("generated:") + nameOf(pattern) + "-mr", size, false, [&](float u, float v) {
    const float h = height(pattern, u, v, seed);
    const bool metal = pattern == Pattern::Metal;
    return glm::vec4(0.0f, metal ? 0.25f + 0.4f * h : 0.5f + 0.4f * h, metal ? 1.0f : 0.0f, 1.0f);
  });
}

}  // namespace fgb::scene::procedural
