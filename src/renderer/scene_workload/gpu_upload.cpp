#include "gpu_upload.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <span>
#include <tuple>

#include "frame_update.hpp"
#include "renderer/shared/meshes.h"
#include "renderer/shared/visbuffer.h"

namespace fgb::render {
namespace {

// The scene's clusters are uploaded as they are: their layout is gpu::ClusterData's.
static_assert(sizeof(scene::Cluster) == sizeof(gpu::ClusterData));
static_assert(offsetof(scene::Cluster, center) == offsetof(gpu::ClusterData, sphere) &&
              offsetof(scene::Cluster, radius) == offsetof(gpu::ClusterData, sphere) + 12);
static_assert(offsetof(scene::Cluster, coneAxis) == offsetof(gpu::ClusterData, cone) &&
              offsetof(scene::Cluster, coneCutoff) == offsetof(gpu::ClusterData, cone) + 12);
static_assert(offsetof(scene::Cluster, firstTriangle) == offsetof(gpu::ClusterData, firstTriangle) &&
              offsetof(scene::Cluster, triangleCount) == offsetof(gpu::ClusterData, triangleCount) &&
              offsetof(scene::Cluster, firstVertex) == offsetof(gpu::ClusterData, firstVertex) &&
              offsetof(scene::Cluster, vertexCount) == offsetof(gpu::ClusterData, vertexCount));
static_assert(offsetof(scene::Cluster, lodCenter) == offsetof(gpu::ClusterData, lodSphere) &&
              offsetof(scene::Cluster, parentCenter) == offsetof(gpu::ClusterData, parentSphere) &&
              offsetof(scene::Cluster, lodError) == offsetof(gpu::ClusterData, lodError) &&
              offsetof(scene::Cluster, parentError) == offsetof(gpu::ClusterData, parentError) &&
              offsetof(scene::Cluster, lodLevel) == offsetof(gpu::ClusterData, lodLevel));

using features::GpuScene;

// Bytes to copy into one buffer, gathered into the staging buffer.
struct PendingBuffer {
  rhi::BufferId target;
  uint64_t stagingOffset = 0;
  uint64_t size = 0;
};
struct PendingMip {
  rhi::TextureId target;
  uint32_t mip = 0;
  uint64_t stagingOffset = 0;
};

class StagingBuilder {
 public:
  uint64_t append(std::span<const std::byte> bytes) {
    const uint64_t offset = (bytes_.size() + 15) & ~uint64_t{15};
    bytes_.resize(offset + bytes.size());
    std::memcpy(bytes_.data() + offset, bytes.data(), bytes.size());
    return offset;
  }
  template <class T>
  uint64_t append(const std::vector<T>& values) {
    return append(std::as_bytes(std::span(values)));
  }
  [[nodiscard]] const std::vector<std::byte>& bytes() const { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
};

// Every shader-visible state a persistent resource may be read in after the upload.
constexpr graph::ImportState kReadState{
    graph::kStageAllCommands,
    graph::kAccessShaderStorageRead | graph::kAccessShaderSampledRead | graph::kAccessVertexAttributeRead |
        graph::kAccessIndexRead | graph::kAccessIndirectCommandRead | graph::kAccessTransferRead,
    graph::Layout::ShaderReadOnly, graph::QueueClass::Graphics};
constexpr graph::ImportState kFreshState{graph::kStageNone, graph::kAccessNone, graph::Layout::Undefined,
                                         graph::QueueClass::Graphics};

class SceneUploader {
 public:
  explicit SceneUploader(rhi::Device& device) : device_(device) {}

  rhi::BufferId buffer(const std::string& name, std::span<const std::byte> bytes, rhi::BufferUsage usage) {
    const uint64_t size = std::max<uint64_t>(bytes.size(), 16);
    const auto id = device_.createBuffer({name, size, usage | rhi::kBufferTransferDst, rhi::MemoryUsage::DeviceLocal});
    if (!bytes.empty()) buffers_.push_back({id, staging_.append(bytes), bytes.size()});
    return id;
  }

  rhi::TextureId texture(const scene::Texture& source) {
    rhi::TextureDesc desc;
    desc.name = source.name;
    desc.format = source.srgb ? graph::Format::R8G8B8A8Srgb : graph::Format::R8G8B8A8Unorm;
    desc.extent = {source.width, source.height, 1};
    desc.mipLevels = uint32_t(source.mips.size());
    desc.usage = rhi::kTextureSampled | rhi::kTextureTransferDst;
    const auto id = device_.createTexture(desc);
    for (uint32_t mip = 0; mip < source.mips.size(); ++mip) {
      const auto& level = source.mips[mip];
      const auto bytes = std::as_bytes(std::span(source.data)).subspan(level.offset, uint64_t{level.width} * level.height * 4);
      mips_.push_back({id, mip, staging_.append(bytes)});
    }
    textureDescs_.push_back({id, desc});
    return id;
  }

  // Runs every gathered copy in one transfer node and waits for it.
  void submit() {
    const auto& bytes = staging_.bytes();
    const auto staging = device_.createBuffer(
        {"scene staging", std::max<uint64_t>(bytes.size(), 16), rhi::kBufferTransferSrc, rhi::MemoryUsage::Upload});
    std::memcpy(device_.mapped(staging).data(), bytes.data(), bytes.size());

    graph::FrameGraph graph;
    auto node = graph.addNode("Scene Upload", graph::NodeType::Transfer);
    node.sideEffect();
    for (const auto& pending : buffers_) {
      auto handle = graph.importBuffer("upload", {pending.size, {}}, rhi::external(pending.target), kFreshState, kReadState);
      node.write(handle, graph::Access::TransferDst);
    }
    for (const auto& [id, desc] : textureDescs_) {
      graph::TextureDesc graphDesc{desc.format, desc.extent, desc.mipLevels, 1, 1, {}, 0};
      auto handle = graph.importTexture(desc.name, graphDesc, rhi::external(id), kFreshState, kReadState);
      node.write(handle, graph::Access::TransferDst);
    }
    node.setJob([staging, buffers = buffers_, mips = mips_](graph::JobContext& context) {
      auto& cmd = rhi::rhiContext(context).cmd();
      for (const auto& pending : buffers) {
        const rhi::BufferCopy region{pending.stagingOffset, 0, pending.size};
        cmd.copyBuffer(staging, pending.target, std::span(&region, 1));
      }
      for (const auto& mip : mips) cmd.copyBufferToTexture(staging, mip.target, mip.stagingOffset, mip.mip);
    });
    node.recordingFixed();
    rhi::GraphOptions options;
    options.name = "scene upload";
    options.timestamps = false;
    auto executable = device_.compile(std::move(graph), options);
    device_.wait(device_.execute(*executable));
  }

 private:
  rhi::Device& device_;
  StagingBuilder staging_;
  std::vector<PendingBuffer> buffers_;
  std::vector<PendingMip> mips_;
  std::vector<std::pair<rhi::TextureId, rhi::TextureDesc>> textureDescs_;
};

template <class T>
std::span<const std::byte> bytesOf(const std::vector<T>& values) {
  return std::as_bytes(std::span(values));
}

std::vector<gpu::Material> gpuMaterials(const scene::Scene& scene, const std::vector<uint32_t>& textureIndices) {
  auto texture = [&](int32_t index) { return index < 0 ? -1 : int32_t(textureIndices.at(uint32_t(index))); };
  std::vector<gpu::Material> result;
  for (const auto& m : scene.materials) {
    gpu::Material out{};
    out.baseColor = m.baseColorFactor;
    out.emissive = glm::vec4(m.emissiveFactor * m.emissiveStrength, m.normalScale);
    out.metallic = m.metallicFactor;
    out.roughness = m.roughnessFactor;
    out.alphaCutoff = m.alphaCutoff;
    out.alphaMode = uint32_t(m.alphaMode);
    out.baseColorTexture = texture(m.baseColorTexture);
    out.normalTexture = texture(m.normalTexture);
    out.metallicRoughnessTexture = texture(m.metallicRoughnessTexture);
    out.emissiveTexture = texture(m.emissiveTexture);
    result.push_back(out);
  }
  return result;
}

uint32_t clusterDrawFlags(const scene::Scene& scene, const scene::Instance& instance) {
  const scene::Material& material = scene.materials[instance.material];
  const glm::mat3 linear(instance.transform);
  const float sx = glm::length(linear[0]), sy = glm::length(linear[1]), sz = glm::length(linear[2]);
  const float largest = std::max({sx, sy, sz}), smallest = std::min({sx, sy, sz});
  uint32_t flags = 0;
  if (!material.doubleSided) flags |= gpu::kClusterSingleSided;
  if (glm::determinant(linear) < 0.0f) flags |= gpu::kClusterMirrored;
  if (smallest > 0.99f * largest) flags |= gpu::kClusterConeUsable;
  if (material.alphaMode == scene::AlphaMode::Mask) flags |= gpu::kClusterAlphaMasked;
  return flags;
}

// Every cluster, of every LOD level, of every opaque and alpha-masked GPU instance, in instance
// order ("Cluster Cull" keeps one cut of each), and each instance's range of them (`ranges`, per
// GPU instance: ClusterGeometry::instanceDraws). `triangles` counts level 0: no cut has more.
std::vector<gpu::ClusterDraw> clusterDraws(const scene::Scene& scene, const GpuScene& gpu, uint64_t& triangles,
                                           std::vector<glm::uvec2>& ranges) {
  std::vector<gpu::ClusterDraw> draws;
  triangles = 0;
  ranges.assign(gpu.instanceCount, glm::uvec2(0u));
  for (const auto& group : gpu.groups) {
    if (group.drawClass == features::DrawClass::Transparent) continue;
    const scene::Mesh& mesh = scene.meshes[group.mesh];
    for (uint32_t slot = group.firstSlot; slot < group.firstSlot + group.capacity; ++slot) {
      ranges[slot] = {uint32_t(draws.size()), mesh.clusterCount};
      const uint32_t flags = clusterDrawFlags(scene, scene.instances[gpu.instanceOrder[slot]]);
      for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c)
        draws.push_back({slot, c, mesh.firstVertex, flags});
      triangles += mesh.triangleCount();
    }
  }
  return draws;
}

// Per cluster vertex (scene::Scene::clusterVertices' order): its position copied out of the
// scene-wide streams, and (w, as uint bits) its vertex in them: one 16-byte load gives both.
std::vector<glm::uvec4> clusterVertexStream(const scene::Scene& scene) {
  std::vector<glm::uvec4> stream(scene.clusterVertices.size(), glm::uvec4(0u));
  for (const scene::Mesh& mesh : scene.meshes) {
    for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c) {
      const scene::Cluster& cluster = scene.clusters[c];
      for (uint32_t v = cluster.firstVertex; v < cluster.firstVertex + cluster.vertexCount; ++v) {
        const uint32_t vertex = mesh.firstVertex + scene.clusterVertices[v];
        const glm::vec3& p = scene.positions[vertex];
        stream[v] = {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z), vertex};
      }
    }
  }
  return stream;
}

// Where a triangle of any LOD level falls in the mesh's index-buffer order: the latest of its
// corners' first uses there (`firstUse`: per mesh-local vertex, the first index-buffer triangle
// using it). For a level-0 triangle that is about its own place (a triangle is where its newest
// corner first appears, or just after); a simplified one, whose corners are the mesh's vertices
// too, sorts among the triangles around those corners.
uint32_t indexOrderKey(const std::vector<uint32_t>& firstUse, const std::array<uint32_t, 3>& corners) {
  return std::max({firstUse[corners[0]], firstUse[corners[1]], firstUse[corners[2]]});
}

// One transparent mesh's clusters, every LOD level, as indexed draws (TransparentClusters),
// appended to `entries` and `indices`. Blending depends on the order an instance's triangles are
// drawn in (a closed glass shell shows its back through its front, and which of the two is drawn
// first changes the pixel), and the image without LOD draws them in the index buffer's order. So
// the draws approximate that order: each cluster's triangles by indexOrderKey, the clusters by
// their triangles' mean key (a cut draws its clusters in entry order). On the atrium's lanterns
// (atrium.scale=8, 640x360) this took the LDR-FLIP that transparent LOD adds at
// render.lod_error=0.25 from 0.0158 in the cooker's order to 0.0021 by the first triangle's key
// and 0.0003 by the mean key.
void appendTransparentMesh(const scene::Scene& scene, const scene::Mesh& mesh,
                           std::vector<gpu::TransparentClusterEntry>& entries, std::vector<uint32_t>& indices) {
  std::vector<uint32_t> firstUse(mesh.vertexCount, UINT32_MAX);
  for (uint32_t i = mesh.indexCount; i-- > 0;) firstUse[scene.indices[mesh.firstIndex + i]] = i / 3;
  struct KeyedCluster {
    uint32_t id = 0;
    std::vector<std::pair<uint32_t, std::array<uint32_t, 3>>> triangles;  // key, mesh-local corners
  };
  std::vector<KeyedCluster> clusters;
  for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.clusterCount; ++c) {
    const scene::Cluster& cluster = scene.clusters[c];
    KeyedCluster keyed{c, {}};
    for (uint32_t t = cluster.firstTriangle; t < cluster.firstTriangle + cluster.triangleCount; ++t) {
      std::array<uint32_t, 3> corners{};
      for (uint32_t k = 0; k < 3; ++k)
        corners[k] =
            scene.clusterVertices[cluster.firstVertex + scene::clusterTriangleCorner(scene.clusterTriangles[t], k)];
      keyed.triangles.emplace_back(indexOrderKey(firstUse, corners), corners);
    }
    std::stable_sort(keyed.triangles.begin(), keyed.triangles.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    clusters.push_back(std::move(keyed));
  }
  const auto meanKey = [](const KeyedCluster& cluster) {
    uint64_t sum = 0;
    for (const auto& triangle : cluster.triangles) sum += triangle.first;
    return cluster.triangles.empty() ? uint64_t{UINT32_MAX} : sum / cluster.triangles.size();
  };
  std::stable_sort(clusters.begin(), clusters.end(),
                   [&](const KeyedCluster& a, const KeyedCluster& b) { return meanKey(a) < meanKey(b); });
  for (const KeyedCluster& cluster : clusters) {
    entries.push_back({cluster.id, uint32_t(indices.size())});
    for (const auto& triangle : cluster.triangles)
      indices.insert(indices.end(), triangle.second.begin(), triangle.second.end());
  }
}

// A transparent mesh's record: its entries and own index range, and what tells whether an
// instance's cut is its own triangles throughout (the parent groups of its level-0 clusters: the
// smallest error, and a sphere holding them all, around the mesh's box centre).
gpu::TransparentMeshClusters transparentMeshClusters(const scene::Scene& scene, const scene::Mesh& mesh,
                                                     uint32_t firstEntry, uint32_t firstIndex) {
  gpu::TransparentMeshClusters out{};
  out.firstEntry = firstEntry;
  out.entryCount = mesh.clusterCount;
  out.vertexOffset = int32_t(mesh.firstVertex);
  out.firstIndex = firstIndex;
  out.indexCount = mesh.indexCount;
  const glm::vec3 centre =
      mesh.localBounds.isEmpty() ? glm::vec3(0.0f) : glm::vec3(0.5 * (mesh.localBounds.min + mesh.localBounds.max));
  float radius = 0.0f;
  out.minParentError = scene::kLodRootError;
  for (uint32_t c = mesh.firstCluster; c < mesh.firstCluster + mesh.baseClusterCount; ++c) {
    const scene::Cluster& cluster = scene.clusters[c];
    out.minParentError = std::min(out.minParentError, cluster.parentError);
    radius = std::max(radius, glm::length(cluster.parentCenter - centre) + cluster.parentRadius);
  }
  // Rounded outwards: the bound must hold the spheres, not nearly.
  out.groupBounds = glm::vec4(centre, std::nextafter(radius * 1.0001f, HUGE_VALF));
  return out;
}

// The clusters of the meshes transparent instances use, as indexed draws (TransparentClusters).
void uploadTransparentClusters(SceneUploader& uploader, const scene::Scene& scene, GpuScene& gpu) {
  std::vector<bool> transparentMesh(scene.meshes.size(), false);
  for (const auto& group : gpu.groups)
    if (group.drawClass == features::DrawClass::Transparent) transparentMesh[group.mesh] = true;
  std::vector<gpu::TransparentMeshClusters> meshes(std::max<size_t>(scene.meshes.size(), 1),
                                                   gpu::TransparentMeshClusters{});
  std::vector<gpu::TransparentClusterEntry> entries;
  std::vector<uint32_t> indices;
  auto& out = gpu.clusterGeometry.transparent;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    if (!transparentMesh[m]) continue;
    const scene::Mesh& mesh = scene.meshes[m];
    meshes[m] = transparentMeshClusters(scene, mesh, uint32_t(entries.size()), uint32_t(indices.size()));
    out.maxEntries = std::max(out.maxEntries, mesh.clusterCount);
    const auto own = std::span(scene.indices).subspan(mesh.firstIndex, mesh.indexCount);
    indices.insert(indices.end(), own.begin(), own.end());
    appendTransparentMesh(scene, mesh, entries, indices);
  }
  if (out.maxEntries == 0) return;
  out.indices = uploader.buffer("transparent cluster indices", bytesOf(indices), rhi::kBufferIndex);
  out.meshes = uploader.buffer("transparent cluster meshes", bytesOf(meshes), rhi::kBufferStorage);
  out.entries = uploader.buffer("transparent cluster entries", bytesOf(entries), rhi::kBufferStorage);
}

void uploadClusters(SceneUploader& uploader, const scene::Scene& scene, GpuScene& gpu) {
  auto& geometry = gpu.clusterGeometry;
  std::vector<glm::uvec2> ranges;
  const auto draws = clusterDraws(scene, gpu, geometry.triangles, ranges);
  geometry.drawCount = uint32_t(draws.size());
  geometry.clusters = uploader.buffer("scene clusters", bytesOf(scene.clusters), rhi::kBufferStorage);
  geometry.packedTriangles =
      uploader.buffer("scene cluster triangles", bytesOf(scene.clusterTriangles), rhi::kBufferStorage);
  geometry.vertices =
      uploader.buffer("scene cluster vertices", bytesOf(clusterVertexStream(scene)), rhi::kBufferStorage);
  geometry.draws = uploader.buffer("cluster draws", bytesOf(draws), rhi::kBufferStorage);
  geometry.instanceDraws = uploader.buffer("cluster draws per instance", bytesOf(ranges), rhi::kBufferStorage);
  uploadTransparentClusters(uploader, scene, gpu);
}

void uploadGeometry(SceneUploader& uploader, const scene::Scene& scene, GpuScene& gpu) {
  StagingBuilder vertices;  // one buffer, four streams
  gpu.streams.positions = vertices.append(scene.positions);
  gpu.streams.normals = vertices.append(scene.normals);
  gpu.streams.tangents = vertices.append(scene.tangents);
  gpu.streams.uvs = vertices.append(scene.uv0);
  gpu.vertices = uploader.buffer("scene vertices", vertices.bytes(), rhi::kBufferVertex | rhi::kBufferStorage);
  gpu.indices = uploader.buffer("scene indices", bytesOf(scene.indices), rhi::kBufferIndex | rhi::kBufferStorage);
}

}  // namespace

GpuScene uploadScene(rhi::Device& device, const scene::Scene& scene, const features::RenderSettings& settings,
                     const features::RenderPath& path) {
  GpuScene gpu;
  gpu.scene = &scene;
  gpu.constants = makeFrameConstants(scene, scene.camera, settings);
  DrawOrder order = drawOrder(scene, scene.camera.position);
  gpu.groups = std::move(order.groups);
  gpu.instanceOrder = std::move(order.instanceOrder);
  gpu.instanceCount = uint32_t(gpu.instanceOrder.size());
  gpu.lightCount = uint32_t(scene.lights.size());

  SceneUploader uploader(device);
  uploadGeometry(uploader, scene, gpu);
  if (path.uploadClusters) uploadClusters(uploader, scene, gpu);
  std::vector<uint32_t> textureIndices;
  for (const auto& texture : scene.textures) {
    gpu.textures.push_back(uploader.texture(texture));
    textureIndices.push_back(device.sampledTextureIndex(gpu.textures.back()));
  }
  gpu.materials = uploader.buffer("scene materials", bytesOf(gpuMaterials(scene, textureIndices)), rhi::kBufferStorage);
  const gpu::Exposure exposure = initialExposure(scene.post);
  gpu.exposure = uploader.buffer("exposure", std::as_bytes(std::span(&exposure, 1)), rhi::kBufferStorage);
  gpu.constants.buffers.x = device.storageBufferIndex(gpu.exposure);
  createFrameBuffers(device, gpu);  // written before each frame (FrameUpdate)
  gpu.materialSampler = device.createSampler({"material", rhi::Filter::Linear, rhi::Filter::Linear, rhi::Filter::Linear,
                                              rhi::AddressMode::Repeat, 8.0f});
  gpu.linearClampSampler = device.createSampler({"linear clamp", rhi::Filter::Linear, rhi::Filter::Linear,
                                                 rhi::Filter::Nearest, rhi::AddressMode::ClampToEdge, 1.0f});
  uploader.submit();
  return gpu;
}

}  // namespace fgb::render
