// The cooked binary encoding of a Scene (see serialize.hpp). Structs with padding are written
// field by field so the bytes (and the content hash) never depend on uninitialised padding.
#include "serialize.hpp"

namespace fgb::scene::detail {
namespace {

template <typename Sink>
void writeMesh(Writer<Sink>& w, const Mesh& m) {
  w.string(m.name);
  w.pod(m.firstVertex);
  w.pod(m.vertexCount);
  w.pod(m.firstIndex);
  w.pod(m.indexCount);
  w.pod(m.localBounds);
  w.pod(m.firstCluster);
  w.pod(m.clusterCount);
  w.pod(m.baseClusterCount);
}

Mesh readMesh(Reader& r) {
  Mesh m;
  m.name = r.string();
  m.firstVertex = r.pod<uint32_t>();
  m.vertexCount = r.pod<uint32_t>();
  m.firstIndex = r.pod<uint32_t>();
  m.indexCount = r.pod<uint32_t>();
  m.localBounds = r.pod<Aabb>();
  m.firstCluster = r.pod<uint32_t>();
  m.clusterCount = r.pod<uint32_t>();
  m.baseClusterCount = r.pod<uint32_t>();
  return m;
}

template <typename Sink>
void writeMaterial(Writer<Sink>& w, const Material& m) {
  w.string(m.name);
  w.pod(m.baseColorFactor);
  w.pod(m.metallicFactor);
  w.pod(m.roughnessFactor);
  w.pod(m.emissiveFactor);
  w.pod(m.emissiveStrength);
  w.pod(m.normalScale);
  w.pod(static_cast<uint32_t>(m.alphaMode));
  w.pod(m.alphaCutoff);
  w.pod(static_cast<uint8_t>(m.doubleSided));
  w.pod(m.baseColorTexture);
  w.pod(m.normalTexture);
  w.pod(m.metallicRoughnessTexture);
  w.pod(m.emissiveTexture);
}

Material readMaterial(Reader& r) {
  Material m;
  m.name = r.string();
  m.baseColorFactor = r.pod<glm::vec4>();
  m.metallicFactor = r.pod<float>();
  m.roughnessFactor = r.pod<float>();
  m.emissiveFactor = r.pod<glm::vec3>();
  m.emissiveStrength = r.pod<float>();
  m.normalScale = r.pod<float>();
  const auto alpha = r.pod<uint32_t>();
  if (alpha > 2) throw CorruptData("bad alpha mode");
  m.alphaMode = static_cast<AlphaMode>(alpha);
  m.alphaCutoff = r.pod<float>();
  m.doubleSided = r.pod<uint8_t>() != 0;
  m.baseColorTexture = r.pod<int32_t>();
  m.normalTexture = r.pod<int32_t>();
  m.metallicRoughnessTexture = r.pod<int32_t>();
  m.emissiveTexture = r.pod<int32_t>();
  return m;
}

template <typename Sink>
void writeTexture(Writer<Sink>& w, const Texture& t) {
  w.string(t.name);
  w.pod(t.width);
  w.pod(t.height);
  w.pod(static_cast<uint8_t>(t.srgb));
  w.array(t.mips);
  w.array(t.data);
}

Texture readTexture(Reader& r) {
  Texture t;
  t.name = r.string();
  t.width = r.pod<uint32_t>();
  t.height = r.pod<uint32_t>();
  t.srgb = r.pod<uint8_t>() != 0;
  t.mips = r.array<MipLevel>();
  t.data = r.array<uint8_t>();
  return t;
}

template <typename Sink>
void writeEmitter(Writer<Sink>& w, const Emitter& e) {
  w.string(e.name);
  w.pod(e.position);
  w.pod(e.rate);
  w.pod(e.lifetime);
  w.pod(e.direction);
  w.pod(e.coneAngleDeg);
  w.pod(e.speedMin);
  w.pod(e.speedMax);
  w.pod(e.colorStart);
  w.pod(e.colorEnd);
  w.pod(e.sizeStart);
  w.pod(e.sizeEnd);
  w.pod(e.maxParticles);
  w.pod(e.seed);
}

Emitter readEmitter(Reader& r) {
  Emitter e;
  e.name = r.string();
  e.position = r.pod<glm::dvec3>();
  e.rate = r.pod<float>();
  e.lifetime = r.pod<float>();
  e.direction = r.pod<glm::vec3>();
  e.coneAngleDeg = r.pod<float>();
  e.speedMin = r.pod<float>();
  e.speedMax = r.pod<float>();
  e.colorStart = r.pod<glm::vec4>();
  e.colorEnd = r.pod<glm::vec4>();
  e.sizeStart = r.pod<float>();
  e.sizeEnd = r.pod<float>();
  e.maxParticles = r.pod<uint32_t>();
  e.seed = r.pod<uint32_t>();
  return e;
}

// Field by field: PointLight has padding after its double position.
template <typename Sink>
void writeLight(Writer<Sink>& w, const PointLight& l) {
  w.pod(l.position);
  w.pod(l.color);
  w.pod(l.intensity);
  w.pod(l.radius);
}

PointLight readLight(Reader& r) {
  PointLight l;
  l.position = r.pod<glm::dvec3>();
  l.color = r.pod<glm::vec3>();
  l.intensity = r.pod<float>();
  l.radius = r.pod<float>();
  return l;
}

template <typename Sink>
void writeSun(Writer<Sink>& w, const DirectionalLight& s) {
  w.pod(static_cast<uint8_t>(s.enabled));
  w.pod(s.direction);
  w.pod(s.color);
  w.pod(s.intensity);
}

DirectionalLight readSun(Reader& r) {
  DirectionalLight s;
  s.enabled = r.pod<uint8_t>() != 0;
  s.direction = r.pod<glm::vec3>();
  s.color = r.pod<glm::vec3>();
  s.intensity = r.pod<float>();
  return s;
}

template <typename Sink>
void writePost(Writer<Sink>& w, const PostSettings& p) {
  w.pod(p.exposure);
  w.pod(static_cast<uint8_t>(p.autoExposure));
  w.pod(p.lightScale);
  w.pod(static_cast<uint8_t>(p.bloom.enabled));
  w.pod(p.bloom.threshold);
  w.pod(p.bloom.knee);
  w.pod(p.bloom.intensity);
  w.pod(p.bloom.radius);
}

PostSettings readPost(Reader& r) {
  PostSettings p;
  p.exposure = r.pod<float>();
  p.autoExposure = r.pod<uint8_t>() != 0;
  p.lightScale = r.pod<float>();
  p.bloom.enabled = r.pod<uint8_t>() != 0;
  p.bloom.threshold = r.pod<float>();
  p.bloom.knee = r.pod<float>();
  p.bloom.intensity = r.pod<float>();
  p.bloom.radius = r.pod<float>();
  return p;
}

template <typename Sink, typename T, typename F>
void writeList(Writer<Sink>& w, const std::vector<T>& items, F&& writeOne) {
  w.pod(static_cast<uint64_t>(items.size()));
  for (const T& item : items) writeOne(w, item);
}

template <typename F>
auto readList(Reader& r, F&& readOne) {
  const auto count = r.pod<uint64_t>();
  std::vector<decltype(readOne(r))> items;
  for (uint64_t i = 0; i < count; ++i) items.push_back(readOne(r));  // each read bounds-checks
  return items;
}

void check(bool ok, const char* what) {
  if (!ok) throw CorruptData(what);
}

void validateTexture(const Texture& t) {
  check(!t.mips.empty() && t.mips[0].width == t.width && t.mips[0].height == t.height, "texture mip 0 size");
  for (const MipLevel& level : t.mips) {
    check(level.offset + uint64_t(level.width) * level.height * 4 <= t.data.size(), "texture mip past its data");
  }
}

void validateScene(const Scene& s) {
  const size_t vertices = s.positions.size();
  check(s.normals.size() == vertices && s.tangents.size() == vertices && s.uv0.size() == vertices,
        "vertex attribute arrays differ in length");
  for (const Mesh& mesh : s.meshes) {
    check(uint64_t(mesh.firstVertex) + mesh.vertexCount <= vertices, "mesh vertex range");
    check(uint64_t(mesh.firstIndex) + mesh.indexCount <= s.indices.size() && mesh.indexCount % 3 == 0,
          "mesh index range");
    for (uint32_t i = 0; i < mesh.indexCount; ++i) check(s.indices[mesh.firstIndex + i] < mesh.vertexCount, "index");
    check(uint64_t(mesh.firstCluster) + mesh.clusterCount <= s.clusters.size(), "mesh cluster range");
    check(mesh.baseClusterCount <= mesh.clusterCount, "mesh level-0 cluster count");
    for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c) {
      const Cluster& cluster = s.clusters[c];
      check(cluster.triangleCount <= kClusterMaxTriangles &&
                uint64_t(cluster.firstTriangle) + cluster.triangleCount <= s.clusterTriangles.size(),
            "cluster triangle range");
      check(cluster.vertexCount <= kClusterMaxVertices &&
                uint64_t(cluster.firstVertex) + cluster.vertexCount <= s.clusterVertices.size(),
            "cluster vertex range");
      for (uint32_t t = 0; t < cluster.triangleCount; ++t) {
        const uint32_t packed = s.clusterTriangles[cluster.firstTriangle + t];
        check(packed >> 24 == 0, "cluster triangle");
        for (uint32_t corner = 0; corner < 3; ++corner)
          check(clusterTriangleCorner(packed, corner) < cluster.vertexCount, "cluster triangle corner");
      }
      for (uint32_t v = 0; v < cluster.vertexCount; ++v)
        check(s.clusterVertices[cluster.firstVertex + v] < mesh.vertexCount, "cluster vertex");
    }
  }
  for (const Instance& instance : s.instances) {
    check(instance.mesh < s.meshes.size() && instance.material < s.materials.size(), "instance reference");
  }
  const auto textureOk = [&](int32_t index) { return index >= -1 && index < int32_t(s.textures.size()); };
  for (const Material& m : s.materials) {
    check(textureOk(m.baseColorTexture) && textureOk(m.normalTexture) && textureOk(m.metallicRoughnessTexture) &&
              textureOk(m.emissiveTexture),
          "material texture reference");
  }
  for (const Texture& t : s.textures) validateTexture(t);
}

}  // namespace

template <typename Sink>
void writeScene(Writer<Sink>& w, const Scene& s) {
  w.array(s.positions);
  w.array(s.normals);
  w.array(s.tangents);
  w.array(s.uv0);
  w.array(s.indices);
  w.array(s.clusters);
  w.array(s.clusterTriangles);
  w.array(s.clusterVertices);
  writeList(w, s.meshes, [](auto& out, const Mesh& m) { writeMesh(out, m); });
  w.array(s.instances);
  writeList(w, s.materials, [](auto& out, const Material& m) { writeMaterial(out, m); });
  writeList(w, s.textures, [](auto& out, const Texture& t) { writeTexture(out, t); });
  writeList(w, s.lights, [](auto& out, const PointLight& l) { writeLight(out, l); });
  writeSun(w, s.sun);
  writeList(w, s.emitters, [](auto& out, const Emitter& e) { writeEmitter(out, e); });
  w.pod(s.camera);
  w.pod(static_cast<uint8_t>(s.hasCamera));
  writePost(w, s.post);
  w.pod(s.repairs);
  writeList(w, s.warnings, [](auto& out, const std::string& text) { out.string(text); });
}

template void writeScene(Writer<VectorSink>&, const Scene&);
template void writeScene(Writer<HashSink>&, const Scene&);

Scene readScene(Reader& r) {
  Scene s;
  s.positions = r.array<glm::vec3>();
  s.normals = r.array<glm::vec3>();
  s.tangents = r.array<glm::vec4>();
  s.uv0 = r.array<glm::vec2>();
  s.indices = r.array<uint32_t>();
  s.clusters = r.array<Cluster>();
  s.clusterTriangles = r.array<uint32_t>();
  s.clusterVertices = r.array<uint32_t>();
  s.meshes = readList(r, readMesh);
  s.instances = r.array<Instance>();
  s.materials = readList(r, readMaterial);
  s.textures = readList(r, readTexture);
  s.lights = readList(r, readLight);
  s.sun = readSun(r);
  s.emitters = readList(r, readEmitter);
  s.camera = r.pod<Camera>();
  s.hasCamera = r.pod<uint8_t>() != 0;
  s.post = readPost(r);
  s.repairs = r.pod<RepairCounters>();
  s.warnings = readList(r, [](Reader& in) { return in.string(); });
  validateScene(s);
  return s;
}

uint64_t hashScene(const Scene& scene) {
  HashSink sink;
  Writer<HashSink> writer(sink);
  writeScene(writer, scene);
  return sink.digest();
}

}  // namespace fgb::scene::detail
