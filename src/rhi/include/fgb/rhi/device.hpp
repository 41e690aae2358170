// The RHI device: creates resources and pipelines, and runs frame graphs. There are no queues,
// command buffers or semaphores in this interface — all GPU work is a frame-graph node; the backend
// compiles a graph once (ExecutableGraph) and executes it every frame.
#pragma once

#include <fgb/graph/compiled_graph.hpp>
#include <fgb/graph/compiler.hpp>
#include <fgb/graph/frame_graph.hpp>
#include <fgb/rhi/types.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fgb::rhi {

struct AdapterInfo {
  uint32_t index = 0;          // position in the backend's enumeration (the --device INDEX)
  std::string name;
  std::string driver;          // driver name + info, e.g. "llvmpipe (Mesa 25.0.7 ...)"
  std::string type;            // "cpu" | "discrete" | "integrated" | "virtual" | "other"
  std::string apiVersion;      // "1.4.305"
  double timestampPeriodNs = 1.0;
  uint32_t timestampValidBits = 64;
  bool hostTimestamps = false; // the device's "GPU" clock is the host clock (CPU implementations)
  std::string uuid;            // VkPhysicalDeviceIDProperties::deviceUUID as 32 hex digits
  uint32_t maxImageDimension2D = 0;  // the largest width or height of a 2D image
  std::vector<std::string> queueFamilies;  // "0: graphics|compute|transfer x1"
  bool usable = true;          // meets the backend's requirements (Vulkan 1.3 features)
  std::string unusableReason;
};

// A render size the adapter cannot hold as one 2D image is bad input: InputError naming
// --width/--height and the adapter's limit (instead of an allocation failing later as "out of
// device memory"). Nothing is checked when the limit is unknown (0).
void checkRenderSize(const AdapterInfo& adapter, uint32_t width, uint32_t height);

struct DeviceOptions {
  std::string selector = "auto";  // auto | lavapipe | gpu | INDEX
  bool validation = false;        // validation + synchronization validation; every message counted
  bool forceDescriptorFallback = false;  // use the non-bindless descriptor path even if supported
  bool debugLabels = true;        // per-node debug-utils labels (when the extension is present)
  uint32_t framesInFlight = 2;    // executions of one graph that may be pending on the GPU
  std::string pipelineCacheDir{};  // on-disk pipeline cache ("" = in memory only)
};

// Pipeline creation so far: count, host time spent in vkCreate*Pipelines, and the on-disk cache's
// state at start ("off", "cold": nothing usable on disk, "warm").
struct PipelineStats {
  uint32_t created = 0;
  double creationMs = 0.0;
  std::string cache = "off";
};

struct GraphOptions {
  std::string name = "graph";
  // Logical queues (1..3): graphics, compute, transfer nodes go to their own queue when > 1. Each
  // logical queue maps to a device queue of a fitting family; logical queues that land on the same
  // device queue are one queue (on lavapipe everything runs on its one queue, with no semaphores).
  // 0: as many as the device offers distinct queues for the three classes.
  uint32_t queues = 0;
  // Test and benchmark aid: keep the logical queues apart even where they share a device queue, so
  // that a one-queue device (lavapipe) still exercises cross-queue submits and semaphores.
  bool separateQueues = false;
  bool cull = true;
  bool alias = true;
  bool timestamps = true;
  // debug.record_every_frame: run every node's job every execution, ignoring the recording keys
  // (graph::NodeBuilder::recordingDependsOn) that otherwise let a node's kept commands be reused.
  bool recordEveryFrame = false;
  // debug.node_buffers: one primary command buffer per node. Otherwise the nodes of one submit share
  // one buffer (a block), kept while every node's key is unchanged and recorded again as a whole
  // when one changed: fewer buffers to submit, and on NVIDIA less GPU time between nodes. The pass
  // calibration (RunMode::Isolated) submits nodes one by one, so it always records per node.
  bool nodeBuffers = false;
  // When set, graph::compile() adds its stages' times to it (CompileOptions::profile).
  graph::CompileProfile* compileProfile = nullptr;
  // Test aid (debug.slow_pass): the alive node named `slowNode` also runs, inside its timestamps and
  // after its own work, a compute dispatch that costs `slowFraction` times the node's own GPU time
  // (calibrated over the first executions, then fixed; see src/rhi/vulkan/src/spin.hpp). It
  // touches no graph resource. InputError when no alive node has that name or its queue cannot
  // run compute work.
  std::string slowNode{};
  double slowFraction = 0.0;
  // Test only: drop every barrier that keeps the layout (same-layout RAW/WAW/WAR), to prove that
  // synchronization validation catches the hazards they prevent.
  bool testDropSameLayoutBarriers = false;
};

enum class RunMode : uint8_t {
  Sequential,  // waits for the previous sequential run to finish on the GPU (timeline-chained)
  Async,       // no ordering with other graphs; completion is polled or reported by a callback
  // Calibration: the device goes idle first, then each node is submitted alone and waited for
  // before the next, so its timestamps give its cost on an otherwise idle GPU. The same recorded
  // work as a Sequential run (kept command buffers are reused). Complete when execute() returns.
  Isolated,
};

struct RunTicket {
  uint32_t graph = kInvalidId;
  uint64_t execution = 0;
};

// GPU times of one execution of a graph.
struct GraphTimings {
  uint64_t execution = 0;
  std::vector<double> nodeMs;  // per declared node; 0 for culled nodes
  std::vector<double> nodeStartMs;  // per declared node, from the execution's first timestamp; -1 if none
  double gpuMs = 0.0;          // first node start to last node end
  // The first node start on the device's timestamp clock, in ms: only differences between
  // executions mean something (the GPU's idle time between frames). -1 if nothing was timed.
  double startMs = -1.0;
};

class ExecutableGraph {
 public:
  virtual ~ExecutableGraph() = default;
  [[nodiscard]] virtual const graph::FrameGraph& declaration() const = 0;
  [[nodiscard]] virtual const graph::CompiledGraph& compiled() const = 0;
  [[nodiscard]] virtual uint64_t executions() const = 0;
  // Host time of the latest execution: blocked waiting for a frame in flight to finish and
  // reading and resetting its queries (throttling), recording its command buffers, and
  // vkQueueSubmit (on lavapipe that call may run the work itself, so it says little about host
  // cost there).
  struct HostTimes {
    double throttleMs = 0.0;
    double recordMs = 0.0;
    double submitMs = 0.0;
    // Compiled nodes whose job ran (recorded) and whose kept commands were submitted again
    // without running it (reused; see NodeBuilder::recordingDependsOn). They add up to the steps.
    uint32_t nodesRecorded = 0;
    uint32_t nodesReused = 0;
  };
  [[nodiscard]] virtual HostTimes lastHostTimes() const = 0;
  // Timings of finished executions not taken yet, oldest first. Never waits for the GPU: results
  // of execution N are normally available while execution N+1 is recorded.
  virtual std::vector<GraphTimings> takeTimings() = 0;
  // The physical object behind a resource of the graph (transient or imported).
  [[nodiscard]] virtual BufferId buffer(uint32_t resource) const = 0;
  [[nodiscard]] virtual TextureId texture(uint32_t resource) const = 0;
};

// The highest sample count in `supported` (a sampleCounts() mask) not above `requested`; 1 if none.
constexpr uint32_t clampSampleCount(uint32_t requested, uint32_t supported) {
  for (uint32_t samples = 64; samples > 1; samples /= 2) {
    if (samples <= requested && (supported & samples) != 0) return samples;
  }
  return 1;
}

// Optional shader capabilities: queried from the device, enabled at device creation where present.
struct ShaderCapabilities {
  bool int64 = false;               // 64-bit integers in shaders (shaderInt64)
  bool bufferInt64Atomics = false;  // 64-bit atomics on storage buffers and shared memory
  // Format::R64Uint storage textures with 64-bit atomics, load and store (Vulkan:
  // VK_EXT_shader_image_atomic_int64, enabled where present): the H100 has them, lavapipe does
  // not. The visibility buffer's image backing (render.vis_backing) needs them.
  bool imageInt64Atomics = false;
};

class Device {
 public:
  virtual ~Device() = default;
  [[nodiscard]] virtual const AdapterInfo& adapter() const = 0;
  // Highest sample count (1, 2, 4, 8) usable for colour and depth attachments on this device.
  [[nodiscard]] virtual uint32_t maxSamples() const = 0;
  // Every sample count usable for colour and depth attachments: bit value N set = N samples
  // supported (VkSampleCountFlags semantics; 1 is always set). Not necessarily contiguous:
  // lavapipe supports {1, 4}.
  [[nodiscard]] virtual uint32_t sampleCounts() const = 0;
  [[nodiscard]] virtual bool bindless() const = 0;
  // CommandBuffer::drawIndexedIndirectCount is available (Vulkan 1.2 drawIndirectCount).
  [[nodiscard]] virtual bool drawIndirectCount() const = 0;
  [[nodiscard]] virtual ShaderCapabilities shaderCapabilities() const { return {}; }
  // Task and mesh shaders (VK_EXT_mesh_shader with its taskShader and meshShader features, enabled
  // where present; drawIndirectCount too, for drawMeshTasksIndirectCount): mesh pipelines
  // (GraphicsPipelineDesc::meshShader) and the kStageTaskShader/kStageMeshShader stages.
  [[nodiscard]] virtual bool meshShaders() const { return false; }
  // Multisampled rasterisation samples at Vulkan's standard sample positions
  // (VkPhysicalDeviceLimits::standardSampleLocations), which a shader may then rely on.
  [[nodiscard]] virtual bool standardSampleLocations() const { return false; }

  virtual BufferId createBuffer(const BufferDesc& desc) = 0;
  virtual TextureId createTexture(const TextureDesc& desc) = 0;
  virtual SamplerId createSampler(const SamplerDesc& desc) = 0;
  virtual PipelineId createGraphicsPipeline(const GraphicsPipelineDesc& desc) = 0;
  virtual PipelineId createComputePipeline(const ComputePipelineDesc& desc) = 0;
  [[nodiscard]] virtual PipelineStats pipelineStats() const = 0;
  // Destroys an object now; the caller guarantees no pending execution still uses it (e.g. after
  // wait() on the run that used it last). Everything else lives as long as the Device.
  virtual void destroyBuffer(BufferId buffer) = 0;
  virtual void destroyTexture(TextureId texture) = 0;
  // Host-visible buffers (Upload, Readback) stay mapped; empty span for device-local ones.
  virtual std::span<std::byte> mapped(BufferId buffer) = 0;

  [[nodiscard]] virtual uint32_t storageBufferIndex(BufferId buffer) const = 0;
  [[nodiscard]] virtual uint32_t sampledTextureIndex(TextureId texture) const = 0;
  // R64Uint textures index a storage-texture table of their own (bindless.glsl's
  // FGB_BINDING_INT64_STORAGE_TEXTURES); other formats share one.
  [[nodiscard]] virtual uint32_t storageTextureIndex(TextureId texture) const = 0;
  [[nodiscard]] virtual uint32_t samplerIndex(SamplerId sampler) const = 0;

  // Compiles a graph for this device (real memory requirements, queue mapping), creates and binds
  // its transient resources, and takes the nodes' jobs. Throws graph::GraphError on bad graphs.
  virtual std::unique_ptr<ExecutableGraph> compile(graph::FrameGraph&& graph, const GraphOptions& options) = 0;
  // Records and submits one execution. Never waits for this execution; waits only when the
  // graph's frames-in-flight are all still pending. `onComplete` (async runs) is called from
  // poll(), execute() or waitIdle() once the GPU finished.
  virtual RunTicket execute(ExecutableGraph& graph, RunMode mode = RunMode::Sequential,
                            std::function<void()> onComplete = {}) = 0;
  [[nodiscard]] virtual bool isComplete(const RunTicket& ticket) const = 0;
  virtual void wait(const RunTicket& ticket) = 0;
  // Invokes the callbacks of finished async runs.
  virtual void poll() = 0;
  virtual void waitIdle() = 0;

  // Validation messages so far (0 with validation off). Each is also printed on stderr.
  [[nodiscard]] virtual uint64_t validationMessages() const = 0;
  [[nodiscard]] virtual std::vector<std::string> validationLog() const = 0;
};

}  // namespace fgb::rhi
