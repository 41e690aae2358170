// The atrium's architectural pieces. Orientation rule for shapes::grid: the face normal is
// cross(dP/du, dP/dv), so every parameterisation below is chosen to make that point outward.
#include "atrium_meshes.hpp"

#include "procedural.hpp"

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace fgb::scene::atrium {
namespace {

constexpr float kPi = glm::pi<float>();

float smooth(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

// Triangles a lathe adds beyond its grid (two fan caps).
double latheGridBudget(double budget, uint32_t radial) { return std::max(2.0, budget - 2.0 * radial); }

MeshData budgetedLathe(const std::string& name, double budget, double aspect, const shapes::ProfileFn& profile,
                       const shapes::RadialFn& wobble, bool capBottom, bool capTop) {
  glm::uvec2 res = shapes::resolutionFor(budget, aspect);
  res = shapes::resolutionFor(latheGridBudget(budget, res.x), aspect);
  return shapes::lathe(name, res.x, res.y, profile, wobble, capBottom, capTop);
}

}  // namespace

MeshData column(const std::string& name, double budget, float height, float radius) {
  // Plinth, torus base, fluted shaft with entasis, flaring capital and abacus.
  const auto profile = [=](float t) {
    float r = radius;
    if (t < 0.07f) {
      r = radius * 1.45f;
    } else if (t < 0.11f) {
      r = radius * (1.15f + 0.2f * std::sin(kPi * (t - 0.07f) / 0.04f));
    } else if (t < 0.88f) {
      const float s = (t - 0.11f) / 0.77f;
      r = radius * (1.0f + 0.06f * std::sin(kPi * s * 0.7f) - 0.1f * s);
    } else if (t < 0.96f) {
      r = radius * (0.9f + 0.6f * smooth(0.88f, 0.96f, t));
    } else {
      r = radius * 1.55f;
    }
    return glm::vec2(r, t * height);
  };
  const auto fluting = [](float theta, float t) {
    const float onShaft = smooth(0.11f, 0.13f, t) * (1.0f - smooth(0.86f, 0.88f, t));
    return 1.0f - 0.035f * onShaft * std::pow(std::abs(std::cos(theta * 12.0f)), 0.5f);
  };
  return budgetedLathe(name, budget, 0.5, profile, fluting, true, true);
}

MeshData arch(const std::string& name, double budget, float depth) {
  // The opening is narrower than the bay so the arch springs from the capitals, not the axes.
  const float r = kArchRadius - 0.25f, w = kArchRadius, h = kArchRise, halfDepth = depth / 2;
  // The outer boundary of a spandrel face: where the ray at angle theta leaves [-w, w] x [0, h].
  const auto outer = [=](float theta) {
    const float c = std::cos(theta), s = std::sin(theta);
    const float reach = std::min(std::abs(c) > 1e-6f ? w / std::abs(c) : 1e9f, s > 1e-6f ? h / s : 1e9f);
    return glm::vec2(c, s) * reach;
  };
  const auto inner = [=](float theta) { return glm::vec2(std::cos(theta), std::sin(theta)) * r; };
  const glm::uvec2 faceRes = shapes::resolutionFor(budget * 0.3, 4.0);
  const glm::uvec2 soffitRes = shapes::resolutionFor(budget * 0.3, 6.0);
  const glm::uvec2 topRes = shapes::resolutionFor(budget * 0.1, 8.0);
  // Front (+z): theta runs clockwise with u so cross(dP/du, dP/dv) = +z.
  MeshData mesh = shapes::grid(name, faceRes.x, faceRes.y, [&](float u, float v) {
    const float theta = kPi * (1.0f - u);
    const glm::vec2 p = glm::mix(inner(theta), outer(theta), v);
    return glm::vec3(p, halfDepth);
  }, glm::vec2(2.0f, 1.0f));
  shapes::append(mesh, shapes::grid("", faceRes.x, faceRes.y, [&](float u, float v) {
    const float theta = kPi * u;
    const glm::vec2 p = glm::mix(inner(theta), outer(theta), v);
    return glm::vec3(p, -halfDepth);
  }, glm::vec2(2.0f, 1.0f)));
  // Soffit (the underside), facing the arch's centre.
  shapes::append(mesh, shapes::grid("", soffitRes.x, soffitRes.y, [&](float u, float v) {
    const float theta = kPi * (1.0f - u);
    return glm::vec3(inner(theta), -halfDepth + depth * v);
  }, glm::vec2(3.0f, 0.5f)));
  shapes::append(mesh, shapes::grid("", topRes.x, topRes.y, [&](float u, float v) {
    return glm::vec3(-w + 2 * w * u, h, halfDepth - depth * v);
  }, glm::vec2(2.0f, 0.5f)));
  return mesh;
}

MeshData wallPanel(const std::string& name, double budget, float width, float height, uint32_t seed) {
  // A plastered wall facing +z with shallow relief, so its triangles are not wasted on a plane.
  const glm::uvec2 res = shapes::resolutionFor(budget, width / height);
  return shapes::grid(name, res.x, res.y, [&](float u, float v) {
    const float relief = 0.03f * procedural::fbm(u, v, 8, 3, seed);
    return glm::vec3(-width / 2 + width * u, height * v, relief);
  }, glm::vec2(width, height) * 0.25f);
}

MeshData cornice(const std::string& name, double budget, float length) {
  // A cove moulding running along x, projecting toward +z from the wall plane, seen from below.
  const glm::uvec2 res = shapes::resolutionFor(budget, 20.0);
  return shapes::grid(name, res.x, res.y, [&](float u, float v) {
    const float z = 0.8f * v;
    const float y = 0.45f * v * v + 0.04f * std::sin(v * 6.0f * kPi);
    return glm::vec3(-length / 2 + length * u, y, z);
  }, glm::vec2(length * 0.5f, 0.5f));
}

MeshData drape(const std::string& name, double budget, uint32_t seed) {
  // A cloth hanging from y = 0 down to y = -4, facing +z, with folds that deepen toward the hem.
  constexpr float kWidth = 2.4f, kLength = 4.0f;
  const glm::uvec2 res = shapes::resolutionFor(budget, kWidth / kLength);
  const float phase = float(seed % 97) * 0.1f;
  return shapes::grid(name, res.x, res.y, [&](float u, float v) {
    const float depth = 0.04f + 0.12f * (1.0f - v);
    const float folds = std::sin(u * 7.0f * 2.0f * kPi + phase) + 0.3f * std::sin(u * 23.0f * kPi + v * 3.0f);
    const float gather = 1.0f - 0.15f * (1.0f - v) * std::sin(u * kPi);
    return glm::vec3((-kWidth / 2 + kWidth * u) * gather, -kLength + kLength * v, depth * folds);
  }, glm::vec2(2.0f, 3.0f));
}

MeshData plant(const std::string& name, double budget, uint32_t seed) {
  // Leaf cards (alpha-masked, double-sided) scattered around the stem.
  constexpr uint32_t kCardDivisions = 2;  // 2x2 quads -> 8 triangles a card
  const auto cards = std::max<uint32_t>(1, static_cast<uint32_t>(budget / (2.0 * kCardDivisions * kCardDivisions)));
  procedural::Rng rng(seed);
  MeshData mesh;
  mesh.name = name;
  for (uint32_t c = 0; c < cards; ++c) {
    const float yaw = rng.range(0.0f, 2 * kPi), pitch = rng.range(-0.6f, 0.9f);
    const float radius = 0.8f * std::sqrt(rng.uniform()), height = rng.range(0.4f, 1.9f);
    const float size = rng.range(0.15f, 0.35f);
    const float bend = rng.range(0.0f, 0.08f);
    MeshData card = shapes::grid("", kCardDivisions, kCardDivisions, [&](float u, float v) {
      return glm::vec3((u - 0.5f) * size, v * size, bend * std::sin(u * kPi));
    }, glm::vec2(0.25f));
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(radius * std::cos(yaw), height, radius * std::sin(yaw)));
    m = glm::rotate(m, yaw, glm::vec3(0, 1, 0));
    m = glm::rotate(m, pitch, glm::vec3(1, 0, 0));
    shapes::transform(card, m);
    shapes::append(mesh, card);
  }
  return mesh;
}

MeshData vase(const std::string& name, double budget) {
  const auto profile = [](float t) {
    const float belly = std::sin(kPi * std::pow(t, 0.8f));
    const float lip = smooth(0.9f, 1.0f, t) * 0.06f;
    return glm::vec2(0.12f + 0.2f * belly + lip, 0.9f * t);
  };
  const auto ribs = [](float theta, float) { return 1.0f + 0.015f * std::cos(theta * 16.0f); };
  return budgetedLathe(name, budget, 1.0, profile, ribs, true, false);
}

MeshData lantern(const std::string& name, double budget) {
  const auto profile = [](float t) { return glm::vec2(0.12f + 0.1f * std::sin(kPi * t), -0.5f + 0.5f * t); };
  const auto panes = [](float theta, float) { return 1.0f + 0.05f * std::abs(std::cos(theta * 3.0f)); };
  return budgetedLathe(name, budget, 1.0, profile, panes, true, true);
}

MeshData brazier(const std::string& name, double budget) {
  // Tripod-like stem that opens into a wide bowl; the fire (an emitter) sits on top.
  const auto profile = [](float t) {
    float r;
    if (t < 0.1f) {
      r = 0.35f - 1.5f * t;                       // foot
    } else if (t < 0.6f) {
      r = 0.2f - 0.1f * smooth(0.1f, 0.3f, t);   // stem
    } else {
      r = 0.1f + 0.55f * smooth(0.6f, 1.0f, t);  // bowl
    }
    return glm::vec2(r, 1.0f * t);
  };
  const auto ornament = [](float theta, float t) {
    return 1.0f + 0.04f * smooth(0.6f, 0.8f, t) * std::cos(theta * 24.0f) * std::sin(t * 40.0f);
  };
  return budgetedLathe(name, budget, 2.0, profile, ornament, true, true);
}

MeshData floorGrid(const std::string& name, double budget) {
  constexpr float kWidth = 2 * kHalfLength, kDepth = 2 * kGalleryWallZ;
  const glm::uvec2 res = shapes::resolutionFor(budget, kWidth / kDepth);
  // u -> +x, v -> -z, so the normal is +y.
  return shapes::grid(name, res.x, res.y, [&](float u, float v) {
    return glm::vec3(-kWidth / 2 + kWidth * u, 0.0f, kDepth / 2 - kDepth * v);
  }, glm::vec2(kWidth, kDepth) * 0.25f);
}

}  // namespace fgb::scene::atrium
