#include "frame_update.hpp"

#include "gpu_upload.hpp"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <tuple>

namespace fgb::render {
namespace {

void writeLights(std::span<gpu::PointLight> out, const scene::Scene& scene, const features::RenderSpace& space) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const auto& light = scene.lights[i];
    // Shading divides by neither the radius nor the distance: 1/R travels in color.w. A radius that
    // is not a positive finite number (scene files refuse it) uploads a light that adds nothing.
    const bool reaches = light.radius > 0.0f && std::isfinite(light.radius);
    const glm::vec3 renderSpace = space.point(light.position);
    const glm::vec3 radiance = reaches ? light.color * light.intensity : glm::vec3(0.0f);
    out[i] = {glm::vec4(renderSpace, light.radius), glm::vec4(radiance, reaches ? 1.0f / light.radius : 0.0f)};
  }
}

template <class T>
std::span<T> mappedAs(rhi::Device& device, rhi::BufferId buffer) {
  const std::span<std::byte> bytes = device.mapped(buffer);
  return {reinterpret_cast<T*>(bytes.data()), bytes.size() / sizeof(T)};
}

}  // namespace

InstanceWriter::InstanceWriter(const scene::Scene& scene) : scene_(scene) {
  for (const auto& source : scene.instances) {
    gpu::Instance instance{};
    instance.normalMatrix = glm::mat4(glm::mat3(glm::transpose(glm::inverse(glm::dmat3(source.transform)))));
    instance.material = source.material;
    instance.triangles = scene.meshes[source.mesh].triangleCount();
    instance.mesh = source.mesh;
    templates_.push_back(instance);
    const auto& mesh = scene.meshes[source.mesh];
    commandTemplates_.push_back({mesh.indexCount, 0, mesh.firstIndex, int32_t(mesh.firstVertex), 0});
  }
  placed_.resize(templates_.size());
  // drawOrder puts the camera-independent groups first; its transparent tail is redone per frame.
  DrawOrder order = drawOrder(scene, scene.camera.position);
  for (const auto& group : order.groups) {
    if (group.drawClass == features::DrawClass::Transparent) break;
    ++sharedGroups_;
    sharedInstances_ += group.capacity;
  }
  groups_ = std::move(order.groups);
  order_ = std::move(order.instanceOrder);
  for (size_t slot = sharedInstances_; slot < order_.size(); ++slot) {
    const auto& bounds = scene.instances[order_[slot]].worldBounds;
    transparent_.push_back({0.5 * (bounds.min + bounds.max), 0.0, order_[slot]});
  }
  staging_.resize(order_.size());
}

void InstanceWriter::sortTransparent(const glm::dvec3& camera) {
  if (sortedFor_ == camera) return;
  sortedFor_ = camera;
  // Back to front, ties in scene order: drawOrder's stable sort of the instances in scene order,
  // as one strict total order, so sorting the last sort's order again gives the same result. That
  // order is nearly sorted already (a camera step swaps a few neighbours), which insertion sort
  // handles in one pass, without the allocation std::stable_sort makes. The multi-draw executes
  // commands in order, which is the blend order. (An instance with empty bounds, whose centre is
  // NaN, draws nothing; it sorts last.)
  for (SortEntry& entry : transparent_) {
    const double distance = glm::distance(entry.center, camera);
    entry.distance = std::isnan(distance) ? -HUGE_VAL : distance;
  }
  const auto before = [](const SortEntry& a, const SortEntry& b) {
    return a.distance > b.distance || (a.distance == b.distance && a.index < b.index);
  };
  for (size_t i = 1; i < transparent_.size(); ++i) {
    if (!before(transparent_[i], transparent_[i - 1])) continue;
    const SortEntry moving = transparent_[i];
    size_t j = i;
    for (; j > 0 && before(moving, transparent_[j - 1]); --j) transparent_[j] = transparent_[j - 1];
    transparent_[j] = moving;
  }
  for (size_t i = 0; i < transparent_.size(); ++i) {
    const uint32_t index = transparent_[i].index;
    if (order_[sharedInstances_ + i] == index) continue;
    order_[sharedInstances_ + i] = index;
    groups_[sharedGroups_ + i] = {scene_.instances[index].mesh, features::DrawClass::Transparent,
                                  uint32_t(sharedInstances_ + i), 1};
  }
}

std::span<const uint32_t> InstanceWriter::transparentOrder() const {
  return std::span(order_).subspan(sharedInstances_);
}

void InstanceWriter::place(const features::RenderSpace& space) {
  if (placedSpace_ == space) return;
  placedSpace_ = space;
  for (size_t index = 0; index < placed_.size(); ++index) {
    const auto& source = scene_.instances[index];
    gpu::Instance& instance = placed_[index];
    instance = templates_[index];
    // Composed in double, then rounded: the float matrix holds only the offset from the anchor.
    instance.model = space.model(source.transform);
    std::tie(instance.boundsMin, instance.boundsMax) = space.bounds(source.worldBounds);
  }
}

void InstanceWriter::writeGroups(size_t firstGroup, std::span<gpu::Instance> instances,
                                 std::span<gpu::DrawCommand> commands) {
  if (firstGroup >= groups_.size()) return;
  const size_t firstSlot = groups_[firstGroup].firstSlot;
  for (size_t group = firstGroup; group < groups_.size(); ++group) {
    const auto& g = groups_[group];
    for (uint32_t slot = g.firstSlot; slot < g.firstSlot + g.capacity; ++slot) {
      staging_[slot] = placed_[order_[slot]];
      staging_[slot].drawGroup = uint32_t(group);
    }
    const auto& mesh = scene_.meshes[g.mesh];
    commands[group] = {mesh.indexCount, 0, mesh.firstIndex, int32_t(mesh.firstVertex), g.firstSlot};
  }
  std::copy(staging_.begin() + std::ptrdiff_t(firstSlot), staging_.end(),
            instances.begin() + std::ptrdiff_t(firstSlot));
}

void InstanceWriter::writeSlot(uint32_t slot, uint32_t group, std::span<gpu::Instance> instances,
                               std::span<gpu::DrawCommand> commands) const {
  gpu::Instance instance = placed_[order_[slot]];
  instance.drawGroup = group;
  instances[slot] = instance;
  gpu::DrawCommand command = commandTemplates_[order_[slot]];
  command.firstInstance = slot;
  commands[group] = command;
}

void InstanceWriter::writeAll(const features::RenderSpace& space, std::span<gpu::Instance> instances,
                              std::span<gpu::DrawCommand> commands) {
  place(space);
  writeGroups(0, instances, commands);
}

void InstanceWriter::writeTransparent(const features::RenderSpace& space, std::span<const uint32_t> held,
                                      std::span<gpu::Instance> instances, std::span<gpu::DrawCommand> commands) {
  place(space);
  // A transparent group holds one instance: slot sharedInstances_ + i is group sharedGroups_ + i.
  const auto order = transparentOrder();
  for (size_t i = 0; i < order.size(); ++i) {
    if (i < held.size() && held[i] == order[i]) continue;
    writeSlot(uint32_t(sharedInstances_ + i), uint32_t(sharedGroups_ + i), instances, commands);
  }
}

CopyContents::Write CopyContents::compare(const features::RenderSpace& space,
                                          std::span<const uint32_t> transparent) const {
  // A copy never written holds no opaque instances either: the first write is everything.
  if (space_ != space) return Write::Everything;
  return std::equal(transparent.begin(), transparent.end(), transparent_.begin(), transparent_.end())
             ? Write::Nothing
             : Write::Transparent;
}

void CopyContents::hold(const features::RenderSpace& space, std::span<const uint32_t> transparent) {
  space_ = space;
  transparent_.assign(transparent.begin(), transparent.end());
}

void createFrameBuffers(rhi::Device& device, features::GpuScene& gpu) {
  const scene::Scene& scene = *gpu.scene;
  const auto buffer = [&](std::string name, uint64_t bytes, rhi::BufferUsage usage) {
    // Host-visible and mapped for life: written by the host, read by shaders (or the copy) directly.
    return device.createBuffer({std::move(name), std::max<uint64_t>(bytes, 16), usage, rhi::MemoryUsage::Upload});
  };
  for (uint32_t slot = 0; slot < features::kFramesInFlight; ++slot) {
    const std::string suffix = " (frame " + std::to_string(slot) + ")";
    features::FrameBuffers& frame = gpu.frames[slot];
    frame.constants = buffer("frame constants" + suffix, sizeof(gpu::FrameConstants), rhi::kBufferStorage);
    frame.instances = buffer("scene instances" + suffix, sizeof(gpu::Instance) * gpu.instanceOrder.size(), rhi::kBufferStorage);
    // At least one light: a valid (unused) entry keeps descriptors simple.
    frame.lights = buffer("scene lights" + suffix, sizeof(gpu::PointLight) * std::max<size_t>(scene.lights.size(), 1),
                          rhi::kBufferStorage);
    frame.commandTemplate = buffer("draw command template" + suffix, sizeof(gpu::DrawCommand) * gpu.groups.size(),
                                   rhi::kBufferTransferSrc | rhi::kBufferStorage);
    std::memset(device.mapped(frame.lights).data(), 0, device.mapped(frame.lights).size());
    frame.constantsIndex = device.storageBufferIndex(frame.constants);
    frame.instancesIndex = device.storageBufferIndex(frame.instances);
    frame.lightsIndex = device.storageBufferIndex(frame.lights);
  }
}

FrameClock FrameClock::of(const scene::Scene& scene, double timeStep) {
  FrameClock clock;
  clock.timeStep = timeStep;
  clock.flies = !scene.cameraPath.empty() && !scene.stillTime;
  if (scene.stillTime) {
    clock.stillTime = *scene.stillTime;
    // Without emitters nothing is simulated: the frame at T needs no frames before it.
    if (!scene.emitters.empty()) clock.stillSteps = uint64_t(std::llround(*scene.stillTime / timeStep)) + 1;
  }
  return clock;
}

FrameUpdate::FrameUpdate(rhi::Device& device, features::GpuScene& gpu, const scene::Scene& scene,
                         const features::RenderSettings& settings, FrameClock clock)
    : gpu_(gpu), scene_(scene), settings_(settings), clock_(clock), path_(scene.cameraPath), instances_(scene) {
  for (uint32_t slot = 0; slot < features::kFramesInFlight; ++slot) {
    const features::FrameBuffers& frame = gpu.frames[slot];
    mapped_[slot] = {device.mapped(frame.constants), mappedAs<gpu::Instance>(device, frame.instances),
                     mappedAs<gpu::PointLight>(device, frame.lights),
                     mappedAs<gpu::DrawCommand>(device, frame.commandTemplate)};
  }
}

void FrameUpdate::writeConstants(uint64_t execution, const scene::Camera& camera, const MappedCopy& copy) {
  gpu::FrameConstants& constants = gpu_.current;
  const CameraKey key{camera.position, camera.target, camera.verticalFovDeg};
  if (lastCamera_ != key) {
    if (lastCamera_ && lastCamera_->fov == key.fov) {
      moveCamera(constants, scene_, camera, settings_);  // the projection and the rest stay
    } else {
      constants = makeFrameConstants(scene_, camera, settings_);
      constants.buffers = gpu_.constants.buffers;
    }
    lastCamera_ = key;
  }
  const bool simulates = clock_.simulates(execution);
  // A still view at camera.time holds its particles at its last simulated step (emits nothing).
  const uint64_t step = simulates ? execution : *clock_.stillSteps - 1;
  constants.simulation = glm::vec4(simulates ? float(clock_.timeStep) : 0.0f, float(clock_.pathTime(execution)), 0.0f, 0.0f);
  constants.step = glm::uvec4(uint32_t(step), execution > 0 ? gpu::kFrameHizValid : 0u, 0u, 0u);
  std::memcpy(copy.constants.data(), &constants, sizeof(constants));
}

void FrameUpdate::write(uint64_t execution) {
  const scene::Camera camera = path_.at(scene_.camera, clock_.pathTime(execution));
  const MappedCopy& mapped = mapped_[execution % features::kFramesInFlight];
  writeConstants(execution, camera, mapped);

  // Render space, and so the instances, bounds and lights, changes only when the camera crosses
  // into another anchor cell; the transparent order changes with any move (it is sorted per
  // position, and written only where the order, not just the distances, changed).
  const auto space = features::RenderSpace::of(scene_, camera.position);
  instances_.sortTransparent(camera.position);
  const auto order = instances_.transparentOrder();
  CopyContents& copy = copies_[execution % features::kFramesInFlight];
  switch (copy.compare(space, order)) {
    case CopyContents::Write::Nothing:
      return;  // this copy already holds this camera's values
    case CopyContents::Write::Transparent:
      instances_.writeTransparent(space, copy.transparent(), mapped.instances, mapped.commands);
      break;
    case CopyContents::Write::Everything:
      instances_.writeAll(space, mapped.instances, mapped.commands);
      writeLights(mapped.lights, scene_, space);
      break;
  }
  copy.hold(space, order);
}

}  // namespace fgb::render
