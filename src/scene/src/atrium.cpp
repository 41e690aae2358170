// The atrium: a Sponza-like two-storey courtyard reproducing the thesis' scene statistics
// (115 instances, ~3.78 M triangles, 28 point lights, one brazier emitter). Repeated elements are
// instanced; the floor absorbs the remaining triangle budget so the total lands within ~0.1%.
#include "atrium.hpp"

#include "atrium_meshes.hpp"
#include "procedural.hpp"

#include <fgb/scene/geometry.hpp>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>

#include <array>
#include <cmath>

namespace fgb::scene {
namespace {

using namespace atrium;
using procedural::Pattern;

constexpr float kHalfTurn = glm::pi<float>();
constexpr uint32_t kBays = 8;  // arches per side per storey; columns = kBays + 1

glm::mat4 at(glm::vec3 position, float yaw = 0.0f) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), position), yaw, glm::vec3(0, 1, 0));
}

float columnX(uint32_t k) { return -kHalfLength + 2.0f + kColumnSpacing * float(k); }
float bayX(uint32_t k) { return columnX(k) + kArchRadius; }

struct Materials {
  uint32_t floor, marble, plaster, sandstone, fabric[3], terracotta, leaves, glass, metal;
};

class AtriumBuilder {
 public:
  explicit AtriumBuilder(const AtriumParams& params) : params_(params) {}

  Scene build() {
    const Materials m = makeMaterials();
    uint64_t placed = placeArchitecture(m) + placeFurnishings(m);
    // The floor takes whatever is left of the budget (one instance).
    const double floorBudget = std::max(2.0, budget(double(kThesisTriangles)) - double(placed));
    const uint32_t floor = mesh(floorGrid("floor", floorBudget));
    addInstance(scene_, floor, m.floor, glm::mat4(1.0f));
    placeLights();
    placeEmitterCameraAndPost();
    return std::move(scene_);
  }

 private:
  double budget(double triangles) const { return triangles * params_.scale; }

  uint32_t mesh(MeshData&& data) {
    repairMesh(data, scene_.repairs, "generator 'atrium'");
    return appendMesh(scene_, std::move(data));
  }

  // Places `count` instances of `meshIndex`, returning the triangles they add.
  uint64_t place(uint32_t meshIndex, uint32_t material, const glm::mat4& transform) {
    addInstance(scene_, meshIndex, material, transform);
    return scene_.meshes[meshIndex].triangleCount();
  }

  int32_t texture(Texture&& t) { return addTexture(scene_, std::move(t)); }
  uint32_t material(Material m) { return addMaterial(scene_, std::move(m)); }

  uint32_t texturedMaterial(const std::string& name, Pattern pattern, float roughness, float normalStrength,
                            glm::vec4 tint = glm::vec4(1.0f)) {
    const uint32_t size = params_.textureSize, seed = params_.seed;
    Material m;
    m.name = name;
    m.baseColorFactor = tint;
    m.metallicFactor = 0.0f;
    m.roughnessFactor = roughness;
    m.baseColorTexture = texture(procedural::baseColorTexture(pattern, size, seed));
    if (normalStrength > 0.0f) m.normalTexture = texture(procedural::normalTexture(pattern, size, seed, normalStrength));
    return material(std::move(m));
  }

  Materials makeMaterials() {
    Materials m{};
    m.floor = texturedMaterial("stone-floor", Pattern::Tiles, 0.8f, 4.0f);
    m.marble = texturedMaterial("marble", Pattern::Marble, 0.35f, 1.5f);
    m.plaster = texturedMaterial("plaster", Pattern::Plaster, 0.9f, 0.0f);
    m.sandstone = texturedMaterial("sandstone", Pattern::Sandstone, 0.85f, 3.0f);
    // The three drapes share one weave texture, tinted per colour.
    m.fabric[0] = texturedMaterial("fabric-red", Pattern::Fabric, 0.95f, 2.0f, {0.6f, 0.08f, 0.06f, 1.0f});
    Material green = scene_.materials[m.fabric[0]];
    green.name = "fabric-green";
    green.baseColorFactor = {0.1f, 0.4f, 0.12f, 1.0f};
    Material blue = green;
    blue.name = "fabric-blue";
    blue.baseColorFactor = {0.08f, 0.15f, 0.5f, 1.0f};
    for (Material* drape : {&green, &blue}) drape->doubleSided = true;
    scene_.materials[m.fabric[0]].doubleSided = true;
    m.fabric[1] = material(green);
    m.fabric[2] = material(blue);
    m.terracotta = texturedMaterial("terracotta", Pattern::Terracotta, 0.7f, 1.0f);
    // The pots are open lathe surfaces without wall thickness: their inside is their back face.
    scene_.materials[m.terracotta].doubleSided = true;
    m.leaves = texturedMaterial("leaves", Pattern::Leaves, 0.6f, 0.0f);
    scene_.materials[m.leaves].alphaMode = AlphaMode::Mask;
    scene_.materials[m.leaves].alphaCutoff = 0.5f;
    scene_.materials[m.leaves].doubleSided = true;
    Material glass;
    glass.name = "lantern-glass";
    glass.baseColorFactor = {1.0f, 0.85f, 0.6f, 0.35f};
    glass.metallicFactor = 0.0f;
    glass.roughnessFactor = 0.1f;
    glass.alphaMode = AlphaMode::Blend;
    glass.emissiveFactor = {1.0f, 0.7f, 0.4f};
    glass.emissiveStrength = 4.0f;
    m.glass = material(glass);
    Material metal;
    metal.name = "brazier-metal";
    metal.baseColorFactor = glm::vec4(1.0f);
    metal.baseColorTexture = texture(procedural::baseColorTexture(Pattern::Metal, params_.textureSize, params_.seed));
    metal.metallicRoughnessTexture =
        texture(procedural::metallicRoughnessTexture(Pattern::Metal, params_.textureSize, params_.seed));
    m.metal = material(metal);
    return m;
  }

  uint64_t placeArchitecture(const Materials& m) {
    const uint32_t groundColumn = mesh(column("column-ground", budget(42000), kGroundColumnHeight, 0.3f));
    const uint32_t upperColumn = mesh(column("column-upper", budget(30000), kUpperColumnHeight, 0.24f));
    const uint32_t groundArch = mesh(arch("arch-ground", budget(24000), 0.7f));
    const uint32_t upperArch = mesh(arch("arch-upper", budget(20000), 0.6f));
    const float wallLength = 2 * kHalfLength;
    const uint32_t galleryWall = mesh(wallPanel("wall-gallery", budget(40000), wallLength, kStoreyHeight, params_.seed));
    const uint32_t endWall = mesh(wallPanel("wall-end", budget(50000), 2 * kGalleryWallZ, 2 * kStoreyHeight, params_.seed + 1));
    const auto slabDivisions = static_cast<uint32_t>(std::max(1.0, std::round(std::sqrt(budget(8000) / 12.0))));
    const uint32_t slab = mesh(shapes::box("balcony-slab", {wallLength, 0.4f, kGalleryWallZ - kArcadeZ}, slabDivisions));
    const uint32_t corniceMesh = mesh(cornice("cornice", budget(20000), wallLength));

    uint64_t triangles = 0;
    const float archBaseGround = kGroundColumnHeight;
    const float archBaseUpper = kUpperColumnBase + kUpperColumnHeight;
    for (float side : {-1.0f, 1.0f}) {
      const float z = side * kArcadeZ;
      for (uint32_t k = 0; k <= kBays; ++k) {
        triangles += place(groundColumn, m.marble, at({columnX(k), 0.0f, z}));
        triangles += place(upperColumn, m.marble, at({columnX(k), kUpperColumnBase, z}));
      }
      for (uint32_t k = 0; k < kBays; ++k) {
        triangles += place(groundArch, m.sandstone, at({bayX(k), archBaseGround, z}));
        triangles += place(upperArch, m.sandstone, at({bayX(k), archBaseUpper, z}));
      }
      // Gallery walls face the courtyard: the mesh faces +z, so the +z wall turns around.
      const float wallYaw = side > 0 ? kHalfTurn : 0.0f;
      triangles += place(galleryWall, m.plaster, at({0.0f, 0.0f, side * kGalleryWallZ}, wallYaw));
      triangles += place(galleryWall, m.plaster, at({0.0f, kStoreyHeight, side * kGalleryWallZ}, wallYaw));
      triangles += place(endWall, m.plaster, at({side * kHalfLength, 0.0f, 0.0f}, -side * kHalfTurn / 2));
      triangles += place(slab, m.sandstone, at({0.0f, kStoreyHeight + 0.2f, side * (kArcadeZ + kGalleryWallZ) / 2}));
      triangles += place(corniceMesh, m.sandstone, at({0.0f, 2 * kStoreyHeight - 0.4f, z}, side > 0 ? kHalfTurn : 0.0f));
    }
    return triangles;
  }

  uint64_t placeFurnishings(const Materials& m) {
    const uint32_t drapeMesh = mesh(drape("drape", budget(32000), params_.seed));
    const uint32_t plantMesh = mesh(plant("plant", budget(40000), params_.seed));
    const uint32_t vaseMesh = mesh(vase("vase", budget(12000)));
    const uint32_t lanternMesh = mesh(lantern("lantern", budget(16000)));
    const uint32_t brazierMesh = mesh(brazier("brazier", budget(150000)));

    uint64_t triangles = 0;
    constexpr std::array<uint32_t, 5> kDrapeBays = {0, 2, 3, 5, 7};
    uint32_t colour = 0;
    for (float side : {-1.0f, 1.0f}) {
      for (uint32_t bay : kDrapeBays) {
        const float yaw = side > 0 ? kHalfTurn : 0.0f;
        triangles += place(drapeMesh, m.fabric[colour++ % 3], at({bayX(bay), 11.0f, side * (kArcadeZ + 0.4f)}, yaw));
      }
      for (uint32_t k = 0; k < kBays; ++k) {
        triangles += place(vaseMesh, m.terracotta, at({bayX(k), 0.0f, side * (kArcadeZ - 0.8f)}));
      }
      for (float end : {-1.0f, 1.0f}) {
        triangles += place(plantMesh, m.leaves, at({end * 12.0f, 0.0f, side * 4.5f}));
      }
    }
    for (float x : kLanternX) triangles += place(lanternMesh, m.glass, at({x, kLanternHeight, 0.0f}));
    triangles += place(brazierMesh, m.metal, at(kBrazier));
    return triangles;
  }

  void placeLights() {
    const glm::vec3 warm(1.0f, 0.78f, 0.55f);
    for (float side : {-1.0f, 1.0f}) {
      for (uint32_t k = 0; k < 7; ++k) {
        scene_.lights.push_back({{columnX(k + 1), 3.2f, side * 8.0f}, warm, 8.0f, 8.0f});
      }
      for (float x : {-10.5f, -3.5f, 3.5f, 10.5f}) {
        scene_.lights.push_back({{x, 9.5f, side * 8.0f}, warm, 6.0f, 7.0f});
      }
    }
    for (float x : kLanternX) scene_.lights.push_back({{x, kLanternHeight - 0.2f, 0.0f}, {1.0f, 0.7f, 0.4f}, 5.0f, 6.0f});
    scene_.lights.push_back({kBrazier + glm::vec3(0, 1.5f, 0), {1.0f, 0.5f, 0.2f}, 20.0f, 10.0f});
    scene_.sun = DirectionalLight{true, glm::normalize(glm::vec3(-0.3f, -1.0f, 0.25f)), {1.0f, 0.95f, 0.85f}, 3.0f};
  }

  void placeEmitterCameraAndPost() {
    Emitter fire;
    fire.name = "brazier-fire";
    fire.position = kBrazier + glm::vec3(0, 1.05f, 0);
    fire.rate = 2000.0f;
    fire.lifetime = 1.2f;
    fire.coneAngleDeg = 25.0f;
    fire.speedMin = 0.6f;
    fire.speedMax = 1.4f;
    fire.colorStart = {8.0f, 3.0f, 0.8f, 1.0f};
    fire.colorEnd = {1.0f, 0.1f, 0.0f, 0.0f};
    fire.sizeStart = 0.12f;
    fire.sizeEnd = 0.03f;
    fire.maxParticles = 4096;
    fire.seed = params_.seed;
    scene_.emitters.push_back(fire);

    scene_.camera.position = kCameraPosition;
    scene_.camera.target = kCameraTarget;
    scene_.camera.up = {0, 1, 0};
    scene_.camera.verticalFovDeg = 60.0f;
    scene_.camera.nearPlane = 0.1f;
    scene_.camera.farPlane = 200.0f;
    scene_.hasCamera = true;
    scene_.post.exposure = 0.6f;  // as in the thesis' figures
    scene_.post.bloom = BloomSettings{true, 1.0f, 0.5f, 0.05f, 1.0f};
  }

  static constexpr std::array<float, 5> kLanternX = {-12.0f, -6.0f, 0.0f, 6.0f, 12.0f};
  static constexpr float kLanternHeight = 3.5f;
  static constexpr glm::vec3 kBrazier{4.0f, 0.0f, 0.0f};
  // Standing in the west part of the courtyard looking east, as the thesis' camera looks down
  // Sponza's nave: the arcades behind and beside the viewer fall outside the frustum.
  static constexpr glm::vec3 kCameraPosition{-11.0f, 2.0f, 0.0f};
  static constexpr glm::vec3 kCameraTarget{10.0f, 3.5f, 1.5f};

  AtriumParams params_;
  Scene scene_;
};

}  // namespace

Scene buildAtrium(const AtriumParams& params) { return AtriumBuilder(params).build(); }

}  // namespace fgb::scene
