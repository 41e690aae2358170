// Private: procedural mesh building blocks for the generators. Every shape takes a triangle budget
// (or explicit resolution) so the atrium can hit the thesis' triangle count at any density.
#pragma once

#include <fgb/scene/geometry.hpp>

#include <functional>

namespace fgb::scene::shapes {

// A (nu x nv)-quad grid over (u, v) in [0,1]^2, mapped by `surface`; uvScale scales the texture
// coordinates. Normals and tangents are computed from the geometry. 2 * nu * nv triangles.
using SurfaceFn = std::function<glm::vec3(float u, float v)>;
MeshData grid(std::string name, uint32_t nu, uint32_t nv, const SurfaceFn& surface, glm::vec2 uvScale);

// Chooses (nu, nv) with nu/nv close to `aspect` so that 2 * nu * nv is close to `triangles`.
glm::uvec2 resolutionFor(double triangles, double aspect);

// Surface of revolution around +Y: profile(t) = (radius, height) for t in [0,1], radial
// modulation wobble(theta, t) multiplies the radius (fluting). Closed with fan caps when requested.
using ProfileFn = std::function<glm::vec2(float t)>;
using RadialFn = std::function<float(float theta, float t)>;
MeshData lathe(std::string name, uint32_t radialSegments, uint32_t profileSegments, const ProfileFn& profile,
               const RadialFn& wobble, bool capBottom, bool capTop);

// Axis-aligned box centred at the origin with `divisions` quads per edge on every face.
MeshData box(std::string name, glm::vec3 size, uint32_t divisions);

// Appends `part` to `into` (same mesh, offset indices).
void append(MeshData& into, const MeshData& part);

// Transforms positions/normals/tangents in place.
void transform(MeshData& mesh, const glm::mat4& m);

}  // namespace fgb::scene::shapes
