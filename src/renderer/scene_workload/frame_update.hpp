// The per-frame update: before each frame's submit, the host writes everything that changes from
// frame to frame into that frame in flight's copy of the per-frame buffers (features::FrameBuffers):
// the frame constants (camera along its path, frustum planes, the particles' step and the HiZ
// flag), render-space instances and lights, and the draw-command template (the transparent
// groups back to front). Recorded commands then hold nothing that changes per frame.
#pragma once

#include "../features/context/gpu_scene.hpp"
#include "../features/context/render_space.hpp"

#include <fgb/rhi/device.hpp>
#include <fgb/scene/camera_path_cursor.hpp>
#include <fgb/scene/scene.hpp>

#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace fgb::render {

// Creates the host-visible per-frame buffers of every frame in flight (sized for the scene).
void createFrameBuffers(rhi::Device& device, features::GpuScene& gpu);

// Where the run is at an execution of the frame graph: the camera's path time and the particles'.
// The run advances by a fixed time step per frame (--time-step). Along a path, execution e is at
// time e * step. A still view at camera.time=T simulates its particles for its first
// round(T / step) + 1 executions (the workload runs those before the first measured frame) and
// then holds them, so its frame equals the path's frame at T. Otherwise, a still view's
// particles advance one step per frame, as they always have.
struct FrameClock {
  double timeStep = 1.0 / 60.0;
  bool flies = false;                  // the scene has a camera path and no camera.time
  double stillTime = 0.0;              // camera.time (0 without it)
  std::optional<uint64_t> stillSteps;  // camera.time with particles: the executions that simulate

  static FrameClock of(const scene::Scene& scene, double timeStep);
  [[nodiscard]] double pathTime(uint64_t execution) const { return flies ? double(execution) * timeStep : stillTime; }
  [[nodiscard]] bool simulates(uint64_t execution) const { return !stillSteps || execution < *stillSteps; }
};

// The render-space instances and draw commands, in draw order, composed at three rates: what
// depends on neither the camera nor the anchor (normal matrices, materials, the opaque and masked
// groups) once; the model matrices and bounds once per render space (anchor); the transparent
// order once per camera position. A frame in flight's copy is rewritten only where it differs: of
// the transparent tail, only the slots whose instance changed (a moving camera swaps a few).
class InstanceWriter {
 public:
  explicit InstanceWriter(const scene::Scene& scene);
  // Sorts the transparent instances back to front from `camera` (drawOrder's order); nothing to do
  // when the camera has not moved since the last sort.
  void sortTransparent(const glm::dvec3& camera);
  // The last sort's transparent instances (scene indices), back to front: the order the commands
  // a copy holds must match.
  [[nodiscard]] std::span<const uint32_t> transparentOrder() const;
  // Every instance (GPU order) and draw command in `space`, into mapped memory.
  void writeAll(const features::RenderSpace& space, std::span<gpu::Instance> instances,
                std::span<gpu::DrawCommand> commands);
  // Only the transparent slots whose instance differs from `held` (the order the copy holds, for a
  // copy that already holds `space`'s instances), and their commands.
  void writeTransparent(const features::RenderSpace& space, std::span<const uint32_t> held,
                        std::span<gpu::Instance> instances, std::span<gpu::DrawCommand> commands);

 private:
  // A transparent instance as the sort needs it, compact so a frame's sort reads a few cache lines.
  struct SortEntry {
    glm::dvec3 center{0.0};  // of its world bounds
    double distance = 0.0;   // from the last sort's camera
    uint32_t index = 0;      // scene instance
  };
  // Composes placed_ for `space` (nothing when it already holds it).
  void place(const features::RenderSpace& space);
  // Groups [firstGroup, end) and their instances, from placed_ in order_.
  void writeGroups(size_t firstGroup, std::span<gpu::Instance> instances, std::span<gpu::DrawCommand> commands);
  // The instance and command of GPU slot `slot` (of group `group`), straight into mapped memory.
  void writeSlot(uint32_t slot, uint32_t group, std::span<gpu::Instance> instances,
                 std::span<gpu::DrawCommand> commands) const;

  const scene::Scene& scene_;
  // Per scene instance: all but the model matrix, the bounds and the group.
  std::vector<gpu::Instance> templates_;
  // Per scene instance, in placedSpace_: the templates with their model matrix and bounds.
  std::vector<gpu::Instance> placed_;
  std::optional<features::RenderSpace> placedSpace_;
  // Per scene instance: its draw command but firstInstance (the slot's).
  std::vector<gpu::DrawCommand> commandTemplates_;
  // The opaque and masked groups, then the last sort's transparent ones; GPU instance i is scene
  // instance order_[i]. The first sharedGroups_ / sharedInstances_ do not depend on the camera.
  std::vector<features::DrawGroup> groups_;
  std::vector<uint32_t> order_;
  size_t sharedGroups_ = 0, sharedInstances_ = 0;
  std::optional<glm::dvec3> sortedFor_;  // the camera position of the last sort
  std::vector<SortEntry> transparent_;   // the last sort's order, back to front
  std::vector<gpu::Instance> staging_;   // writeAll's instances, copied to mapped memory in one go
};

// What one frame in flight's copy of the instances, lights and draw commands holds (its render
// space and transparent order), and so what a frame must rewrite in it.
class CopyContents {
 public:
  enum class Write { Nothing, Transparent, Everything };
  // What to write so that the copy holds `space` and the `transparent` order (scene indices, back
  // to front).
  [[nodiscard]] Write compare(const features::RenderSpace& space, std::span<const uint32_t> transparent) const;
  // The transparent order the copy holds (empty before the first write).
  [[nodiscard]] std::span<const uint32_t> transparent() const { return transparent_; }
  // Records that the copy now holds `space` and `transparent`.
  void hold(const features::RenderSpace& space, std::span<const uint32_t> transparent);

 private:
  std::optional<features::RenderSpace> space_;  // none before the first write
  std::vector<uint32_t> transparent_;
};

class FrameUpdate {
 public:
  FrameUpdate(rhi::Device& device, features::GpuScene& gpu, const scene::Scene& scene,
              const features::RenderSettings& settings, FrameClock clock);

  // Writes execution `execution`'s copy. The caller has waited for the execution that last read
  // it (kFramesInFlight earlier). Writes the constants; rewrites the instances, lights and command
  // template only when the render space (anchor) changed since that copy was written, and else the
  // transparent instances and commands only when their order changed. So a camera moving within
  // its anchor's cell writes only the constants (and a still camera writes the rest once per copy).
  void write(uint64_t execution);

  [[nodiscard]] const FrameClock& clock() const { return clock_; }

 private:
  // One frame in flight's per-frame buffers as mapped memory: mapped for life, looked up once.
  struct MappedCopy {
    std::span<std::byte> constants;
    std::span<gpu::Instance> instances;
    std::span<gpu::PointLight> lights;
    std::span<gpu::DrawCommand> commands;
  };

  // Writes this frame's constants into `copy` (and gpu_.current): the camera's part only when the
  // camera moved since the last frame.
  void writeConstants(uint64_t execution, const scene::Camera& camera, const MappedCopy& copy);

  features::GpuScene& gpu_;
  const scene::Scene& scene_;
  const features::RenderSettings& settings_;
  FrameClock clock_;
  scene::CameraPathCursor path_;  // the frames' cameras, one segment's setup kept
  std::array<MappedCopy, features::kFramesInFlight> mapped_;
  std::array<CopyContents, features::kFramesInFlight> copies_;
  // The camera gpu_.current's camera part was made for (it keeps it between frames, and each frame
  // overwrites only the step): a still camera computes its constants once.
  struct CameraKey {
    glm::dvec3 position{0.0}, target{0.0};
    float fov = 0.0f;
    bool operator==(const CameraKey&) const = default;
  };
  std::optional<CameraKey> lastCamera_;
  InstanceWriter instances_;
};

}  // namespace fgb::render
