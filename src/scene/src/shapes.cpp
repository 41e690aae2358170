// Procedural mesh building blocks.
#include "shapes.hpp"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace fgb::scene::shapes {

MeshData grid(std::string name, uint32_t nu, uint32_t nv, const SurfaceFn& surface, glm::vec2 uvScale) {
  MeshData mesh;
  mesh.name = std::move(name);
  nu = std::max(nu, 1u);
  nv = std::max(nv, 1u);
  mesh.positions.reserve(size_t(nu + 1) * (nv + 1));
  mesh.uv0.reserve(size_t(nu + 1) * (nv + 1));
  for (uint32_t j = 0; j <= nv; ++j) {
    for (uint32_t i = 0; i <= nu; ++i) {
      const float u = float(i) / float(nu), v = float(j) / float(nv);
      mesh.positions.push_back(surface(u, v));
      mesh.uv0.push_back(glm::vec2(u, v) * uvScale);
    }
  }
  mesh.indices.reserve(size_t(nu) * nv * 6);
  for (uint32_t j = 0; j < nv; ++j) {
    for (uint32_t i = 0; i < nu; ++i) {
      const uint32_t a = j * (nu + 1) + i, b = a + 1, c = a + (nu + 1), d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  }
  computeNormals(mesh);
  computeTangents(mesh);
  return mesh;
}

glm::uvec2 resolutionFor(double triangles, double aspect) {
  const double quads = std::max(1.0, triangles / 2.0);
  const double nv = std::max(1.0, std::round(std::sqrt(quads / aspect)));
  const double nu = std::max(1.0, std::round(quads / nv));
  return {static_cast<uint32_t>(nu), static_cast<uint32_t>(nv)};
}

namespace {

void addCap(MeshData& mesh, uint32_t ringStart, uint32_t radialSegments, float y, bool facingUp) {
  // A fan around a centre vertex; ring vertices are duplicated so the cap gets its own normal.
  const auto centre = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.push_back(glm::vec3(0.0f, y, 0.0f));
  mesh.uv0.push_back(glm::vec2(0.5f));
  const uint32_t first = centre + 1;
  for (uint32_t i = 0; i <= radialSegments; ++i) {
    const glm::vec3 p = mesh.positions[ringStart + i];
    mesh.positions.push_back(glm::vec3(p.x, y, p.z));
    const float angle = glm::two_pi<float>() * float(i) / float(radialSegments);
    mesh.uv0.push_back(glm::vec2(0.5f + 0.5f * std::cos(angle), 0.5f + 0.5f * std::sin(angle)));
  }
  for (uint32_t i = 0; i < radialSegments; ++i) {
    // Ring vertices run clockwise seen from above (theta decreases), see lathe().
    if (facingUp) {
      mesh.indices.insert(mesh.indices.end(), {centre, first + i, first + i + 1});
    } else {
      mesh.indices.insert(mesh.indices.end(), {centre, first + i + 1, first + i});
    }
  }
}

}  // namespace

MeshData lathe(std::string name, uint32_t radialSegments, uint32_t profileSegments, const ProfileFn& profile,
               const RadialFn& wobble, bool capBottom, bool capTop) {
  radialSegments = std::max(radialSegments, 3u);
  profileSegments = std::max(profileSegments, 1u);
  // The profile runs bottom to top; with u = angle and v = t, the grid winds counter-clockwise
  // seen from outside when theta decreases with u -- hence the minus sign.
  MeshData mesh = grid(std::move(name), radialSegments, profileSegments,
                       [&](float u, float v) {
                         const float theta = -glm::two_pi<float>() * u;
                         const glm::vec2 rh = profile(v);
                         const float r = rh.x * wobble(theta, v);
                         return glm::vec3(r * std::cos(theta), rh.y, r * std::sin(theta));
                       },
                       glm::vec2(4.0f, 4.0f));
  const uint32_t ring = radialSegments + 1;
  mesh.normals.clear();
  mesh.tangents.clear();
  if (capBottom) addCap(mesh, 0, radialSegments, mesh.positions[0].y, false);
  if (capTop) addCap(mesh, profileSegments * ring, radialSegments, mesh.positions[profileSegments * ring].y, true);
  computeNormals(mesh);
  computeTangents(mesh);
  return mesh;
}

MeshData box(std::string name, glm::vec3 size, uint32_t divisions) {
  MeshData mesh;
  mesh.name = std::move(name);
  const glm::vec3 h = size * 0.5f;
  // Each face: origin corner, u axis, v axis (u x v points outward).
  const glm::vec3 faces[6][3] = {
      {{h.x, -h.y, h.z}, {0, 0, -2 * h.z}, {0, 2 * h.y, 0}},   {{-h.x, -h.y, -h.z}, {0, 0, 2 * h.z}, {0, 2 * h.y, 0}},
      {{-h.x, h.y, h.z}, {2 * h.x, 0, 0}, {0, 0, -2 * h.z}},   {{-h.x, -h.y, -h.z}, {2 * h.x, 0, 0}, {0, 0, 2 * h.z}},
      {{-h.x, -h.y, h.z}, {2 * h.x, 0, 0}, {0, 2 * h.y, 0}},   {{h.x, -h.y, -h.z}, {-2 * h.x, 0, 0}, {0, 2 * h.y, 0}}};
  for (const auto& face : faces) {
    const MeshData side = grid("", divisions, divisions,
                               [&](float u, float v) { return face[0] + face[1] * u + face[2] * v; },
                               glm::vec2(glm::length(face[1]), glm::length(face[2])) * 0.5f);
    append(mesh, side);
  }
  return mesh;
}

void append(MeshData& into, const MeshData& part) {
  const auto offset = static_cast<uint32_t>(into.positions.size());
  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
  into.tangents.insert(into.tangents.end(), part.tangents.begin(), part.tangents.end());
  into.uv0.insert(into.uv0.end(), part.uv0.begin(), part.uv0.end());
  for (uint32_t index : part.indices) into.indices.push_back(index + offset);
}

void transform(MeshData& mesh, const glm::mat4& m) {
  const glm::mat3 linear(m);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  for (glm::vec3& p : mesh.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
  for (glm::vec3& n : mesh.normals) n = glm::normalize(normalMatrix * n);
  for (glm::vec4& t : mesh.tangents) t = glm::vec4(glm::normalize(linear * glm::vec3(t)), t.w);
}

}  // namespace fgb::scene::shapes
