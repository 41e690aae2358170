// The city: a grid of streets lined by buildings, so that from the street most of the scene hides
// behind the nearest facades (the occlusion-culling scene of issue 26). Buildings are built from
// a few dozen archetypes (width class, floors, style), each one mesh for the masonry and one for
// the glass, instanced on every lot; street lamps carry the point lights.
//
// Facades are flat-shaded boxes and quads: a window is a recess (four reveals and a pane), a sill,
// a lintel or a pilaster beside it, a mullion or a transom inside, and a string course runs along
// each floor. So each triangle is a visible feature rather than a subdivided plane, and distant
// blocks cost what their windows cost. Their hard edges (split normals) are borders the LOD
// simplifier keeps, so the facades simplify little: the count the cut draws stays honest too.
#include "city.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fgb/scene/geometry.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <map>
#include <tuple>

#include "procedural.hpp"
#include "shapes.hpp"

namespace fgb::scene {
namespace {

using procedural::Pattern;

constexpr float kPi = glm::pi<float>();
constexpr float kBlockSize = kCityPitch - kCityStreetWidth;  // 44 m of buildings between streets
constexpr float kLotGap = 1.0f;                              // between neighbouring buildings
constexpr float kGroundFloor = 4.5f, kFloor = 3.3f, kParapet = 1.0f;
constexpr float kKerb = 0.15f;  // pavement height above the road
constexpr float kLampHeight = 5.2f;
constexpr std::array<uint32_t, 9> kFloorChoices = {3, 4, 5, 6, 7, 8, 10, 12, 14};
constexpr uint32_t kFacadeTints = 5;

// ---- flat-shaded quads -------------------------------------------------------------------------

// Appends quads with their own four vertices (flat normals, hard edges). UVs are the planar
// projection along the quad's main axis, 4 m per texture repeat, so neighbouring coplanar quads
// continue one texture.
class Quads {
 public:
  explicit Quads(std::string name) { mesh_.name = std::move(name); }

  // The quad (o, o + du, o + du + dv, o + dv), wound so that its normal points along `outward`.
  void face(glm::vec3 o, glm::vec3 du, glm::vec3 dv, glm::vec3 outward) {
    if (glm::dot(glm::cross(du, dv), outward) < 0.0f) std::swap(du, dv);
    const glm::vec3 normal = glm::normalize(glm::cross(du, dv));
    const auto base = static_cast<uint32_t>(mesh_.positions.size());
    for (const glm::vec3 p : {o, o + du, o + du + dv, o + dv}) {
      mesh_.positions.push_back(p);
      mesh_.normals.push_back(normal);
      mesh_.uv0.push_back(planarUv(p, normal));
    }
    mesh_.indices.insert(mesh_.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }

  // An axis-aligned box [lo, hi]; `faces` selects +x, -x, +y, -y, +z, -z (bits 0..5).
  void box(glm::vec3 lo, glm::vec3 hi, uint32_t faces = 0x3f) {
    const glm::vec3 s = hi - lo;
    const glm::vec3 x(s.x, 0, 0), y(0, s.y, 0), z(0, 0, s.z);
    if (faces & 1u) face({hi.x, lo.y, lo.z}, y, z, {1, 0, 0});
    if (faces & 2u) face(lo, y, z, {-1, 0, 0});
    if (faces & 4u) face({lo.x, hi.y, lo.z}, x, z, {0, 1, 0});
    if (faces & 8u) face(lo, x, z, {0, -1, 0});
    if (faces & 16u) face({lo.x, lo.y, hi.z}, x, y, {0, 0, 1});
    if (faces & 32u) face(lo, x, y, {0, 0, -1});
  }

  void append(const MeshData& part) { shapes::append(mesh_, part); }

  // Places everything added since `from` with `m` (a facade built flat, turned onto its side).
  void transformFrom(size_t from, const glm::mat4& m) {
    MeshData part;
    part.positions.assign(mesh_.positions.begin() + long(from), mesh_.positions.end());
    part.normals.assign(mesh_.normals.begin() + long(from), mesh_.normals.end());
    shapes::transform(part, m);
    std::copy(part.positions.begin(), part.positions.end(), mesh_.positions.begin() + long(from));
    std::copy(part.normals.begin(), part.normals.end(), mesh_.normals.begin() + long(from));
    for (size_t i = from; i < mesh_.positions.size(); ++i)
      mesh_.uv0[i] = planarUv(mesh_.positions[i], mesh_.normals[i]);
  }

  size_t vertexCount() const { return mesh_.positions.size(); }

  MeshData take() {
    if (mesh_.tangents.size() != mesh_.positions.size()) {
      mesh_.tangents.clear();
      computeTangents(mesh_);
    }
    return std::move(mesh_);
  }

 private:
  static glm::vec2 planarUv(glm::vec3 p, glm::vec3 n) {
    const glm::vec3 a = glm::abs(n);
    glm::vec2 uv;
    if (a.y >= a.x && a.y >= a.z) {
      uv = {p.x, p.z};
    } else if (a.x >= a.z) {
      uv = {n.x > 0 ? -p.z : p.z, -p.y};
    } else {
      uv = {n.z > 0 ? p.x : -p.x, -p.y};
    }
    return uv * 0.25f;
  }

  MeshData mesh_;
};

// ---- buildings ---------------------------------------------------------------------------------

// What a building mesh depends on; every lot with the same archetype instances the same meshes.
struct Archetype {
  uint32_t lotsAcross = 2;  // lots along the block's x side: 2 (21 m wide) or 3 (13.7 m)
  uint32_t floors = 3;      // above the ground floor
  uint32_t style = 0;       // 0: sills, lintels and mullions, string courses; 1: pilasters, transoms
  auto operator<=>(const Archetype&) const = default;
};

struct BuildingMeshes {
  uint32_t masonry = 0, glass = 0;
};

float lotWidth(uint32_t lotsAcross) {
  return kBlockSize / float(lotsAcross);
}

// One side of a building, built flat: u along +x from 0 to `length`, y up, the wall plane at
// z = 0 facing +z. Window panes go to `glass`.
class FacadeBuilder {
 public:
  FacadeBuilder(Quads& masonry, Quads& glass, const Archetype& a) : m_(masonry), g_(glass), a_(a) {}

  void build(float length) {
    const float bayTarget = a_.style == 0 ? 3.0f : 2.6f;
    const auto bays = std::max(1u, static_cast<uint32_t>(std::lround(length / bayTarget)));
    const float bay = length / float(bays);
    for (uint32_t k = 0; k < bays; ++k) shopfront(float(k) * bay, bay);
    for (uint32_t f = 0; f < a_.floors; ++f) {
      const float y0 = kGroundFloor + float(f) * kFloor;
      for (uint32_t k = 0; k < bays; ++k) window(float(k) * bay, bay, y0);
      if (a_.style == 0) m_.box({-0.05f, y0 - 0.1f, 0.0f}, {length + 0.05f, y0 + 0.1f, 0.15f}, 0x1f);  // string course
    }
    const float top = kGroundFloor + float(a_.floors) * kFloor;
    m_.face({0, top, 0}, {length, 0, 0}, {0, kParapet, 0}, {0, 0, 1});
    // Fascia over the shops and the cornice under the parapet's cap.
    m_.box({-0.1f, kGroundFloor - 0.6f, 0.0f}, {length + 0.1f, kGroundFloor - 0.05f, 0.2f}, 0x1f);
    m_.box({-0.35f, top - 0.4f, 0.0f}, {length + 0.35f, top, 0.35f}, 0x1f);
  }

 private:
  // A wall with a recessed opening [u0, u1] x [v0, v1] inside the rectangle [x0, x1] x [y0, y1]:
  // four wall quads around the opening, four reveals of depth `depth` and the pane at its back.
  void opening(float x0, float x1, float y0, float y1, float u0, float u1, float v0, float v1, float depth) {
    const glm::vec3 out(0, 0, 1);
    m_.face({x0, y0, 0}, {u0 - x0, 0, 0}, {0, y1 - y0, 0}, out);
    m_.face({u1, y0, 0}, {x1 - u1, 0, 0}, {0, y1 - y0, 0}, out);
    m_.face({u0, y0, 0}, {u1 - u0, 0, 0}, {0, v0 - y0, 0}, out);
    m_.face({u0, v1, 0}, {u1 - u0, 0, 0}, {0, y1 - v1, 0}, out);
    const glm::vec3 in(0, 0, -depth);
    m_.face({u0, v0, 0}, in, {0, v1 - v0, 0}, {1, 0, 0});
    m_.face({u1, v0, 0}, in, {0, v1 - v0, 0}, {-1, 0, 0});
    m_.face({u0, v0, 0}, in, {u1 - u0, 0, 0}, {0, 1, 0});
    m_.face({u0, v1, 0}, in, {u1 - u0, 0, 0}, {0, -1, 0});
    g_.face({u0, v0, -depth}, {u1 - u0, 0, 0}, {0, v1 - v0, 0}, out);
    // The pane's frame at the back of the recess: its inner and front faces (the rest touch the
    // reveals or the pane).
    constexpr float kBar = 0.06f, kThick = 0.05f;
    const float back = -depth, front = -depth + kThick;
    m_.box({u0, v0, back}, {u0 + kBar, v1, front}, 0x11);
    m_.box({u1 - kBar, v0, back}, {u1, v1, front}, 0x12);
    m_.box({u0 + kBar, v0, back}, {u1 - kBar, v0 + kBar, front}, 0x14);
    m_.box({u0 + kBar, v1 - kBar, back}, {u1 - kBar, v1, front}, 0x18);
  }

  void shopfront(float x, float bay) {
    const float margin = 0.1f * bay;
    opening(x, x + bay, 0.0f, kGroundFloor, x + margin, x + bay - margin, 0.5f, kGroundFloor - 0.9f, 0.3f);
    // The door's frame bar through the middle of the window.
    const float mid = x + bay / 2;
    m_.box({mid - 0.05f, 0.5f, -0.3f}, {mid + 0.05f, kGroundFloor - 0.9f, -0.22f}, 0x13);
  }

  void window(float x, float bay, float y0) {
    const bool classic = a_.style == 0;
    const float width = (classic ? 0.5f : 0.62f) * bay;
    const float sill = y0 + (classic ? 0.9f : 0.7f), head = sill + (classic ? 1.7f : 2.0f);
    const float u0 = x + (bay - width) / 2, u1 = u0 + width;
    constexpr float kDepth = 0.22f;
    opening(x, x + bay, y0, y0 + kFloor, u0, u1, sill, head, kDepth);
    // The sill below the opening, projecting from the wall.
    m_.box({u0 - 0.1f, sill - 0.08f, 0.0f}, {u1 + 0.1f, sill, 0.12f}, 0x1f);
    if (classic) {
      m_.box({u0 - 0.15f, head + 0.05f, 0.0f}, {u1 + 0.15f, head + 0.25f, 0.1f}, 0x1f);  // lintel
      const float mid = (u0 + u1) / 2;  // mullion, inside the recess in front of the pane
      m_.box({mid - 0.04f, sill, -kDepth}, {mid + 0.04f, head, -kDepth + 0.06f}, 0x13);
    } else {
      const float transom = head - 0.5f;
      m_.box({u0, transom - 0.04f, -kDepth}, {u1, transom + 0.04f, -kDepth + 0.06f}, 0x1c);
      m_.box({x - 0.15f, y0, 0.0f}, {x + 0.15f, y0 + kFloor, 0.1f}, 0x13);  // pilaster at the bay's edge
    }
  }

  Quads& m_;
  Quads& g_;
  Archetype a_;
};

// A rooftop: the roof, the parapet's inner faces and cap, and a few plant boxes (seeded by the
// archetype so that every instance of it carries the same).
void roof(Quads& m, float w, float d, float top, const Archetype& a) {
  constexpr float kWall = 0.25f;
  m.face({-w / 2, top, -d / 2}, {w, 0, 0}, {0, 0, d}, {0, 1, 0});
  const float cap = top + kParapet;
  m.box({-w / 2, top, -d / 2}, {w / 2, cap, -d / 2 + kWall}, 0x14);
  m.box({-w / 2, top, d / 2 - kWall}, {w / 2, cap, d / 2}, 0x24);
  m.box({-w / 2, top, -d / 2}, {-w / 2 + kWall, cap, d / 2}, 0x05);
  m.box({w / 2 - kWall, top, -d / 2}, {w / 2, cap, d / 2}, 0x06);
  procedural::Rng rng(uint64_t(a.lotsAcross) * 1000003u + a.floors * 101u + a.style);
  const uint32_t units = 1 + uint32_t(rng.next() % 3);
  for (uint32_t i = 0; i < units; ++i) {
    const glm::vec3 size(rng.range(1.5f, 4.0f), rng.range(1.0f, 3.0f), rng.range(1.5f, 4.0f));
    const glm::vec3 at(rng.range(-w / 2 + 1 + size.x / 2, w / 2 - 1 - size.x / 2), top,
                       rng.range(-d / 2 + 1 + size.z / 2, d / 2 - 1 - size.z / 2));
    m.box(at - glm::vec3(size.x / 2, 0, size.z / 2), at + glm::vec3(size.x / 2, size.y, size.z / 2), 0x37);
  }
  if (a.style == 0) {  // a water tank on the classic blocks
    MeshData tank = shapes::lathe(
        "", 16, 4, [](float t) { return glm::vec2(1.2f, 2.5f * t); }, [](float, float) { return 1.0f; }, false, true);
    shapes::transform(tank, glm::translate(glm::mat4(1.0f), {w / 4, top + 1.5f, -d / 4}));
    m.append(tank);
  }
}

// Both meshes of one archetype: footprint centred on the origin, x across the lot, facades on
// all four sides, ground at y = 0.
std::pair<MeshData, MeshData> buildingMeshes(const Archetype& a) {
  const std::string name =
      "building-" + std::to_string(a.lotsAcross) + "x" + std::to_string(a.floors) + "-s" + std::to_string(a.style);
  Quads masonry(name), glass(name + "-glass");
  const float w = lotWidth(a.lotsAcross) - kLotGap, d = kBlockSize / 2 - kLotGap;
  // Each side: its length, and where its facade's origin goes and how it turns (the facade's +x
  // along the side, its +z outward).
  const std::array<std::tuple<float, glm::vec3, float>, 4> sides = {{{w, {-w / 2, 0, d / 2}, 0.0f},
                                                                     {d, {w / 2, 0, d / 2}, kPi / 2},
                                                                     {w, {w / 2, 0, -d / 2}, kPi},
                                                                     {d, {-w / 2, 0, -d / 2}, 3 * kPi / 2}}};
  for (const auto& [length, origin, yaw] : sides) {
    const size_t masonryFrom = masonry.vertexCount(), glassFrom = glass.vertexCount();
    FacadeBuilder(masonry, glass, a).build(length);
    const glm::mat4 place = glm::rotate(glm::translate(glm::mat4(1.0f), origin), yaw, glm::vec3(0, 1, 0));
    masonry.transformFrom(masonryFrom, place);
    glass.transformFrom(glassFrom, place);
  }
  roof(masonry, w, d, kGroundFloor + float(a.floors) * kFloor, a);
  return {masonry.take(), glass.take()};
}

// ---- street furniture --------------------------------------------------------------------------

// A tapering pole on a wider foot, and the globe on top of it (emissive; the light sits in it).
MeshData lampPost() {
  return shapes::lathe(
      "lamp-post", 10, 6, [](float t) { return glm::vec2(t < 0.08f ? 0.16f : 0.09f - 0.03f * t, kLampHeight * t); },
      [](float, float) { return 1.0f; }, true, true);
}

MeshData lampGlobe() {
  return shapes::lathe(
      "lamp-globe", 12, 8, [](float t) { return glm::vec2(0.05f + 0.25f * std::sin(kPi * t), kLampHeight + 0.5f * t); },
      [](float, float) { return 1.0f; }, true, true);
}

// ---- the city ----------------------------------------------------------------------------------

glm::dmat4 at(glm::dvec3 position, double yaw = 0.0) {
  return glm::rotate(glm::translate(glm::dmat4(1.0), position), yaw, glm::dvec3(0, 1, 0));
}

class CityBuilder {
 public:
  explicit CityBuilder(const CityParams& params)
      : params_(params), first_(-int(params.blocks / 2)), rng_(params.seed) {}

  Scene build() {
    makeMaterials();
    placeGround();
    placeBuildings();
    placeLamps();
    placeSunCameraAndPost();
    return std::move(scene_);
  }

 private:
  // Street line k (x = k * pitch and z = k * pitch), k in [first_, first_ + blocks].
  float line(int k) const { return float(k) * kCityPitch; }
  int lastLine() const { return first_ + int(params_.blocks); }

  uint32_t mesh(MeshData&& data) {
    repairMesh(data, scene_.repairs, "generator 'city'");
    return appendMesh(scene_, std::move(data));
  }

  int32_t texture(Texture&& t) { return addTexture(scene_, std::move(t)); }
  uint32_t material(Material m) { return addMaterial(scene_, std::move(m)); }

  // A material on a pattern's textures, made once per pattern and shared by its tints.
  uint32_t textured(const std::string& name, Pattern pattern, float roughness, float normalStrength, glm::vec4 tint) {
    auto [it, inserted] = patternTextures_.try_emplace(pattern, -1, -1);
    if (inserted) {
      it->second.first = texture(procedural::baseColorTexture(pattern, params_.textureSize, params_.seed));
      if (normalStrength > 0.0f) {
        it->second.second =
            texture(procedural::normalTexture(pattern, params_.textureSize, params_.seed, normalStrength));
      }
    }
    Material m;
    m.name = name;
    m.baseColorFactor = tint;
    m.metallicFactor = 0.0f;
    m.roughnessFactor = roughness;
    m.baseColorTexture = it->second.first;
    m.normalTexture = it->second.second;
    return material(std::move(m));
  }

  void makeMaterials() {
    facade_[0] = textured("plaster-cream", Pattern::Plaster, 0.9f, 1.0f, {1.0f, 1.0f, 0.95f, 1.0f});
    facade_[1] = textured("plaster-ochre", Pattern::Plaster, 0.9f, 1.0f, {1.0f, 0.8f, 0.55f, 1.0f});
    facade_[2] = textured("plaster-grey", Pattern::Plaster, 0.85f, 1.0f, {0.65f, 0.68f, 0.72f, 1.0f});
    facade_[3] = textured("sandstone", Pattern::Sandstone, 0.85f, 3.0f, glm::vec4(1.0f));
    facade_[4] = textured("brick", Pattern::Terracotta, 0.8f, 2.0f, {0.9f, 0.75f, 0.7f, 1.0f});
    asphalt_ = textured("asphalt", Pattern::Metal, 0.95f, 0.0f, {0.3f, 0.3f, 0.32f, 1.0f});
    pavement_ = textured("pavement", Pattern::Tiles, 0.8f, 4.0f, glm::vec4(1.0f));
    Material dark;
    dark.name = "window-glass";
    dark.baseColorFactor = {0.05f, 0.07f, 0.1f, 1.0f};
    dark.metallicFactor = 0.0f;
    dark.roughnessFactor = 0.15f;
    glass_ = material(dark);
    Material lit = dark;  // a lit room behind the pane
    lit.name = "window-lit";
    lit.emissiveFactor = {1.0f, 0.75f, 0.45f};
    lit.emissiveStrength = 1.5f;
    litGlass_ = material(lit);
    Material metal;
    metal.name = "lamp-metal";
    metal.baseColorFactor = {0.12f, 0.13f, 0.12f, 1.0f};
    metal.metallicFactor = 1.0f;
    metal.roughnessFactor = 0.45f;
    metal_ = material(metal);
    Material globe;
    globe.name = "lamp-globe";
    globe.baseColorFactor = {1.0f, 0.95f, 0.85f, 1.0f};
    globe.metallicFactor = 0.0f;
    globe.roughnessFactor = 0.3f;
    globe.emissiveFactor = {1.0f, 0.85f, 0.6f};
    globe.emissiveStrength = 6.0f;
    globeMaterial_ = material(globe);
  }

  // The road and the pavements are grids of cells no larger than kGroundCell. The cells were
  // first a workaround: the visibility buffer's raster used to drop a triangle with a corner
  // behind the eye (docs/architecture/lod.md, "The cut"; fixed since), and at eye height the
  // ground in view starts 3 m ahead, so smaller cells kept every visible ground triangle wholly in
  // front. They stay, because the city's goldens and cooked geometry are made of them; the LOD
  // cut merges them again in the distance.
  static constexpr float kGroundCell = 1.5f;

  void placeGround() {
    // The road: one grid under the whole city and its edge streets.
    const float lo = line(first_) - kCityStreetWidth, hi = line(lastLine()) + kCityStreetWidth, size = hi - lo;
    const auto cells = static_cast<uint32_t>(std::ceil(size / kGroundCell));
    const uint32_t road = mesh(shapes::grid(
        "road", cells, cells, [&](float u, float v) { return glm::vec3(lo + size * u, 0.0f, hi - size * v); },
        glm::vec2(size * 0.25f)));
    addInstance(scene_, road, asphalt_, glm::dmat4(1.0));
    const uint32_t slab = mesh(pavementSlab(kBlockSize + 6.0f));
    forEachBlock([&](glm::dvec2 centre) { addInstance(scene_, slab, pavement_, at({centre.x, 0.0, centre.y})); });
  }

  // Each block stands on a pavement slab, kerb high: a fine top grid and four kerb faces.
  static MeshData pavementSlab(float size) {
    const auto cells = static_cast<uint32_t>(std::ceil(size / kGroundCell));
    Quads slab("pavement");
    slab.append(shapes::grid(
        "", cells, cells, [&](float u, float v) { return glm::vec3(-size / 2 + size * u, kKerb, size / 2 - size * v); },
        glm::vec2(size * 0.25f)));
    const glm::vec3 lo(-size / 2, 0.0f, -size / 2), hi(size / 2, kKerb, size / 2);
    slab.box(lo, hi, 0x33);
    return slab.take();
  }

  template <typename Fn>
  void forEachBlock(Fn&& fn) const {
    for (int bz = first_; bz < lastLine(); ++bz) {
      for (int bx = first_; bx < lastLine(); ++bx) {
        fn(glm::dvec2(line(bx) + kCityPitch / 2, line(bz) + kCityPitch / 2));
      }
    }
  }

  const BuildingMeshes& meshesFor(const Archetype& a) {
    auto it = archetypes_.find(a);
    if (it == archetypes_.end()) {
      auto [masonry, glass] = buildingMeshes(a);
      it = archetypes_.emplace(a, BuildingMeshes{mesh(std::move(masonry)), mesh(std::move(glass))}).first;
    }
    return it->second;
  }

  // Each block: 2 or 3 lots along x, 2 along z, a building on each with its floors, style,
  // facade material, lit windows or not and which way it faces drawn from the seed.
  void placeBuildings() {
    forEachBlock([&](glm::dvec2 centre) {
      const uint32_t across = 2 + uint32_t(rng_.next() % 2);
      const double width = lotWidth(across);
      for (uint32_t j = 0; j < 2; ++j) {
        for (uint32_t i = 0; i < across; ++i) {
          Archetype a;
          a.lotsAcross = across;
          a.floors = kFloorChoices[rng_.next() % kFloorChoices.size()];
          a.style = uint32_t(rng_.next() % 2);
          const BuildingMeshes& meshes = meshesFor(a);
          const uint32_t tint = uint32_t(rng_.next() % kFacadeTints);
          const bool lit = rng_.uniform() < 0.35f;
          const double yaw = (rng_.next() % 2) ? double(kPi) : 0.0;
          const glm::dvec3 position(centre.x - kBlockSize / 2 + width * (i + 0.5), kKerb,
                                    centre.y - kBlockSize / 2 + kBlockSize / 4 * (2 * j + 1));
          addInstance(scene_, meshes.masonry, facade_[tint], at(position, yaw));
          addInstance(scene_, meshes.glass, lit ? litGlass_ : glass_, at(position, yaw));
        }
      }
    });
  }

  // Two lamps a block side, on alternate pavements, along every street; each carries a light.
  void placeLamps() {
    const uint32_t post = mesh(lampPost()), globe = mesh(lampGlobe());
    const double pavement = kCityStreetWidth / 2 - 1.2;
    const auto lamp = [&](glm::dvec3 foot) {
      addInstance(scene_, post, metal_, at(foot));
      addInstance(scene_, globe, globeMaterial_, at(foot));
      scene_.lights.push_back({foot + glm::dvec3(0, kLampHeight + 0.2, 0), {1.0f, 0.82f, 0.6f}, 24.0f, 18.0f});
    };
    for (int k = first_; k <= lastLine(); ++k) {
      for (int b = first_; b < lastLine(); ++b) {
        const double along = line(b) + kCityPitch / 2, quarter = kBlockSize / 4;
        lamp({line(k) + pavement, kKerb, along - quarter});
        lamp({line(k) - pavement, kKerb, along + quarter});
        lamp({along - quarter, kKerb, line(k) - pavement});
        lamp({along + quarter, kKerb, line(k) + pavement});
      }
    }
  }

  void placeSunCameraAndPost() {
    // Late afternoon: a low warm sun from the south-west, so streets one way lie in the light.
    scene_.sun = DirectionalLight{true, glm::normalize(glm::vec3(0.55f, -0.45f, -0.7f)), {1.0f, 0.85f, 0.65f}, 2.5f};
    // Standing on the street z = 0, west of the crossing at the origin, looking east along it.
    scene_.camera.position = {-50.0, 1.7, 3.0};
    scene_.camera.target = {0.0, 4.0, 3.0};
    scene_.camera.up = {0, 1, 0};
    scene_.camera.verticalFovDeg = 60.0f;
    scene_.camera.nearPlane = 0.1f;
    scene_.camera.farPlane = 1000.0f;
    scene_.hasCamera = true;
    scene_.post.exposure = 0.6f;
    scene_.post.bloom = BloomSettings{true, 1.0f, 0.5f, 0.05f, 1.0f};
  }

  CityParams params_;
  int first_;
  procedural::Rng rng_;
  Scene scene_;
  std::map<Pattern, std::pair<int32_t, int32_t>> patternTextures_;
  std::map<Archetype, BuildingMeshes> archetypes_;
  std::array<uint32_t, kFacadeTints> facade_{};
  uint32_t asphalt_ = 0, pavement_ = 0, glass_ = 0, litGlass_ = 0, metal_ = 0, globeMaterial_ = 0;
};

}  // namespace

Scene buildCity(const CityParams& params) {
  return CityBuilder(params).build();
}

}  // namespace fgb::scene
