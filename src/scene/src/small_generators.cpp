// Showcase (feature scenes) and the numerical-stability stress generators.
#include "small_generators.hpp"

#include "procedural.hpp"
#include "shapes.hpp"

#include <fgb/scene/texture.hpp>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>
#include <limits>

namespace fgb::scene {
namespace {

constexpr float kPi = glm::pi<float>();

uint32_t addRepaired(Scene& scene, MeshData&& mesh, const std::string& context,
                     const std::function<void(MeshData&)>& corrupt) {
  if (corrupt) corrupt(mesh);
  repairMesh(mesh, scene.repairs, context);
  return appendMesh(scene, std::move(mesh));
}

MeshData sphere(uint32_t segments) {
  return shapes::lathe("sphere", segments * 2, segments,
                       [](float t) {
                         const float phi = kPi * (0.02f + 0.96f * t);  // stop short of the poles
                         return glm::vec2(0.5f * std::sin(phi), -0.5f * std::cos(phi));
                       },
                       [](float, float) { return 1.0f; }, true, true);
}

glm::vec3 hueColor(float hue) {
  return glm::clamp(glm::abs(glm::mod(hue * 6.0f + glm::vec3(0, 4, 2), 6.0f) - 3.0f) - 1.0f, 0.0f, 1.0f);
}

}  // namespace

Scene buildShowcase(const ShowcaseParams& p, const std::string& context, const std::function<void(MeshData&)>& corrupt) {
  Scene scene;
  const uint32_t shapesMeshes[3] = {addRepaired(scene, sphere(24), context, corrupt),
                                    addRepaired(scene, shapes::box("box", glm::vec3(0.8f), 4), context, corrupt),
                                    addRepaired(scene, shapes::lathe("pillar", 32, 16,
                                                                     [](float t) { return glm::vec2(0.25f, t * 1.2f - 0.6f); },
                                                                     [](float, float) { return 1.0f; }, true, true),
                                                context, corrupt)};
  const auto columns = static_cast<uint32_t>(std::ceil(std::sqrt(double(p.objects))));
  for (uint32_t i = 0; i < p.objects; ++i) {
    Material m;
    m.name = "object-" + std::to_string(i);
    m.baseColorFactor = glm::vec4(hueColor(float(i) / float(std::max(1u, p.objects))), 1.0f);
    m.metallicFactor = (i % 3 == 0) ? 1.0f : 0.0f;
    m.roughnessFactor = 0.2f + 0.6f * float(i % 4) / 3.0f;
    m.alphaMode = p.alpha;
    if (p.alpha == AlphaMode::Blend) m.baseColorFactor.a = 0.4f;
    if (p.alpha == AlphaMode::Mask) {
      m.baseColorTexture = static_cast<int32_t>(scene.textures.size());
      scene.textures.push_back(procedural::baseColorTexture(procedural::Pattern::Leaves, 128, p.seed));
    }
    m.doubleSided = p.alpha != AlphaMode::Opaque;
    if (p.emissive) {
      m.emissiveFactor = glm::vec3(m.baseColorFactor);
      m.emissiveStrength = 8.0f;
    }
    scene.materials.push_back(m);
    const float x = (float(i % columns) - float(columns - 1) / 2) * 1.5f;
    const float z = -(float(i / columns)) * 1.5f;
    addInstance(scene, shapesMeshes[i % 3], i, glm::translate(glm::mat4(1.0f), {x, 0.6f, z}));
  }
  if (p.floor) {
    Material floor;
    floor.name = "floor";
    floor.metallicFactor = 0.0f;
    floor.roughnessFactor = 0.8f;
    floor.baseColorTexture = static_cast<int32_t>(scene.textures.size());
    scene.textures.push_back(procedural::baseColorTexture(procedural::Pattern::Tiles, 128, p.seed));
    scene.materials.push_back(floor);
    const uint32_t mesh = addRepaired(scene, shapes::grid("floor", 32, 32, [](float u, float v) {
      return glm::vec3(-10 + 20 * u, 0.0f, 10 - 20 * v);
    }, glm::vec2(5.0f)), context, corrupt);
    addInstance(scene, mesh, static_cast<uint32_t>(scene.materials.size() - 1), glm::mat4(1.0f));
  }
  procedural::Rng rng(p.seed);
  for (uint32_t i = 0; i < p.lights; ++i) {
    const float angle = 2 * kPi * float(i) / float(p.lights);
    scene.lights.push_back({{4.0f * std::cos(angle), 2.0f + rng.range(0.0f, 1.0f), -2.0f + 4.0f * std::sin(angle)},
                            hueColor(rng.uniform()) * 0.7f + 0.3f, 6.0f, 8.0f});
  }
  if (p.sun) scene.sun = DirectionalLight{true, glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f)), glm::vec3(1.0f), 2.0f};
  scene.camera.position = {0.0f, 3.0f, 6.0f};
  scene.camera.target = {0.0f, 0.5f, -1.5f};
  scene.hasCamera = true;
  return scene;
}

Scene buildStressFar(const AtriumParams& atrium, double offset) {
  Scene placed;
  // In double: the scene model keeps world placement in double, so 1e7 m loses nothing here.
  mergeScene(placed, buildAtrium(atrium), glm::translate(glm::dmat4(1.0), glm::dvec3(offset, 0.0, offset)));
  placed.post = PostSettings{};
  placed.post.exposure = 0.6f;
  return placed;
}

Scene buildStressDepth(const AtriumParams& atrium) {
  Scene scene = buildAtrium(atrium);
  scene.camera.nearPlane = 1e-4f;
  scene.camera.farPlane = 1e5f;
  return scene;
}

Scene buildStressLights(const AtriumParams& atrium, uint32_t count, uint32_t seed) {
  Scene scene = buildAtrium(atrium);
  scene.lights.clear();
  procedural::Rng rng(seed);
  for (uint32_t i = 0; i < count; ++i) {
    // Log-spaced over twelve decades: 1e-6 ... 1e6.
    const double exponent = count > 1 ? -6.0 + 12.0 * double(i) / double(count - 1) : 0.0;
    const glm::vec3 position(rng.range(-15.0f, 15.0f), rng.range(0.2f, 11.0f), rng.range(-9.5f, 9.5f));
    scene.lights.push_back({position, glm::vec3(1.0f), static_cast<float>(std::pow(10.0, exponent)), rng.range(1.0f, 12.0f)});
  }
  return scene;
}

Scene buildStressTriangles(uint32_t count, uint32_t seed) {
  // Four kinds, cycling: slivers (aspect 1e4), huge (1e5 m edges), degenerate (a repeated index)
  // and zero-area (three collinear points). The last two are removed and counted by repairMesh.
  procedural::Rng rng(seed);
  MeshData mesh;
  mesh.name = "stress-triangles";
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 origin(rng.range(-20.0f, 20.0f), rng.range(0.0f, 10.0f), rng.range(-40.0f, 0.0f));
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    switch (i % 4) {
      case 0:
        mesh.positions.insert(mesh.positions.end(), {origin, origin + glm::vec3(10, 0, 0), origin + glm::vec3(5, 1e-3f, 0)});
        break;
      case 1:
        mesh.positions.insert(mesh.positions.end(),
                              {origin, origin + glm::vec3(1e5f, 0, -1e5f), origin + glm::vec3(-1e5f, 0, -1e5f)});
        break;
      case 2: mesh.positions.insert(mesh.positions.end(), {origin, origin + glm::vec3(1, 0, 0), origin + glm::vec3(0, 1, 0)}); break;
      default:
        mesh.positions.insert(mesh.positions.end(), {origin, origin + glm::vec3(1, 1, 0), origin + glm::vec3(2, 2, 0)});
        break;
    }
    if (i % 4 == 2) {
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 1});
    } else {
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    }
  }
  Scene scene;
  repairMesh(mesh, scene.repairs, "generator 'stress-triangles'");
  const uint32_t index = appendMesh(scene, std::move(mesh));
  Material material;
  material.name = "stress";
  material.metallicFactor = 0.0f;
  material.doubleSided = true;
  scene.materials.push_back(material);
  addInstance(scene, index, 0, glm::mat4(1.0f));
  scene.lights.push_back({{0, 5, -10}, glm::vec3(1.0f), 10.0f, 50.0f});
  scene.camera.position = {0, 5, 10};
  scene.camera.target = {0, 3, -20};
  scene.camera.farPlane = 1e6f;
  scene.hasCamera = true;
  return scene;
}

Scene buildStressNan(double fraction, uint32_t seed) {
  procedural::Rng rng(seed);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  auto lace = [&](MeshData& mesh) {
    auto hit = [&] { return rng.uniform() < fraction; };
    for (glm::vec3& p : mesh.positions) if (hit()) p.y = nan;
    for (glm::vec3& n : mesh.normals) if (hit()) n = rng.uniform() < 0.5f ? glm::vec3(nan) : glm::vec3(0.0f);
    for (glm::vec4& t : mesh.tangents) if (hit()) t.x = inf;
    for (glm::vec2& uv : mesh.uv0) if (hit()) uv.x = nan;
  };
  ShowcaseParams params;
  params.seed = seed;
  Scene scene = buildShowcase(params, "generator 'stress-nan'", lace);
  // Shading singularities the renderer must survive without a NaN: a light lying in the floor's
  // plane and one 5 cm above it (distance -> 0 for the fragments around them) and mirror-smooth
  // materials (roughness 0).
  scene.lights.push_back({{0.0, 0.0, 1.0}, glm::vec3(1.0f), 4.0f, 3.0f});
  scene.lights.push_back({{1.5, 0.05, 1.0}, glm::vec3(1.0f), 4.0f, 3.0f});
  for (Material& material : scene.materials) {
    if (material.name == "object-0" || material.name == "object-1") material.roughnessFactor = 0.0f;
  }
  return scene;
}

}  // namespace fgb::scene
