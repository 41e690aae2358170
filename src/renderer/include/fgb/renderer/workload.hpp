// What the harness renders: a Workload is one scene on one device, ready to render frames through
// the frame graph. The harness (fgbench run/bless/dot) sees only this interface; the built-in proof
// scene (issue 2) and the full renderer (issue 4) implement it. No Vulkan types leak through.
#pragma once

#include <fgb/core/knob_registry.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fgb::render {

struct DeviceDescription {
  uint32_t index = 0;
  std::string name;
  std::string driver;        // driver name + version, e.g. "llvmpipe (Mesa 25.0.7)"
  std::string type;          // "cpu" | "discrete" | "integrated" | "virtual" | "other"
  std::string apiVersion;    // "1.4.305"
  double timestampPeriodNs = 1.0;
  bool hostTimestamps = false;  // true where GPU timestamps are really the host clock (lavapipe)
  std::vector<std::string> queueFamilies;  // "0: graphics|compute|transfer x1" ...
  std::string uuid;                        // 32 hex digits (Vulkan deviceUUID): finds the device in the driver's tools
};

struct WorkloadConfig {
  std::string scenePath;      // a scenes/*.json file or "builtin:proof"
  std::string device = "auto";
  uint32_t width = 0;         // 0: scene default
  uint32_t height = 0;
  uint32_t msaa = 0;          // 0: scene default; clamped to the device (warning on stderr)
  // The sweep's references: MSAA above what the render path draws with is lowered to it (the
  // visibility buffer's 1) instead of refused, so one reference MSAA serves every path.
  bool clampMsaaToPath = false;
  bool validation = false;    // validation + synchronization validation; messages are errors
  std::map<std::string, std::string> knobs;  // --set key=value
  std::string cacheDir;       // cooked-asset cache ("" = default)
  // --check-finite: a reduction node after every pass that writes float colour data counts its
  // NaN / Inf / above-half-of-R16F-max pixels (nonFiniteCounts()); off: those nodes do not exist.
  bool checkFinite = false;
  // --capture: the last frame's outputs of these nodes (capturedPasses()); `capture` off: none are
  // declared; an empty list: every node with an image output. A name that is no node of the frame
  // is bad input (InputError listing the nodes).
  bool capture = false;
  std::vector<std::string> captureNodes;
  // --time-step: seconds between frames, for the camera along its path (camera.path) and the
  // particles' simulation step. 0: the scene file's render.time_step, else 1/60.
  double timeStep = 0.0;
};

// --check-finite counts of one pass (the last rendered frame): pixels with a NaN, an Inf, or a
// finite magnitude above half of R16F's maximum (32752) in some channel of a float texture it wrote.
struct NonFiniteCounts {
  std::string pass;
  uint64_t nan = 0;
  uint64_t inf = 0;
  uint64_t overHalfMax = 0;
  [[nodiscard]] bool bad() const { return nan + inf + overHalfMax > 0; }
};

struct PassTiming {
  std::string name;
  std::string queue;   // "graphics" | "compute" | "transfer"
  bool culled = false;
  double gpuMs = 0.0;  // 0 for culled passes
  double gpuStartMs = -1.0;  // start relative to the frame's first timestamp; < 0 if not reported
};

struct FrameTiming {
  std::vector<PassTiming> passes;  // every declared pass, in declaration order
  double gpuFrameMs = 0.0;         // first pass start to last pass end on the GPU
  // The first pass start on the device's timestamp clock (ms): differences between frames give
  // the GPU's idle time between them. -1 where unknown.
  double gpuFrameStartMs = -1.0;
  // Host time the frame costs: writing its per-frame values (camera, instances, lights) and
  // recording its command buffers (the frame graph's executor and the features' jobs). Not the
  // time blocked while the GPU finishes an earlier frame in flight, nor vkQueueSubmit, which on
  // lavapipe may execute the frame itself (GPU time showing up on the host).
  double cpuFrameMs = 0.0;
  double submitMs = 0.0;       // vkQueueSubmit of the frame (host)
  uint32_t nodesRecorded = 0;  // compiled nodes whose job recorded this frame
  uint32_t nodesReused = 0;    // compiled nodes whose kept commands were submitted again
  // Along a camera path: the frame's path time, seconds (render it alone with camera.time=T).
  // Negative for a still camera.
  double pathTimeS = -1.0;
};

// Linear RGBA float pixels, row-major, top row first.
struct ImageRGBA32F {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> pixels;  // width * height * 4
};

// --capture: one image a node wrote, as the next nodes read it (the last frame).
enum class CaptureContent {
  Color,       // linear RGBA (8-bit sRGB images decoded to linear)
  Depth,       // one float per pixel in r (g = b = r, a = 1)
  Visibility,  // r: depth (from the key), g: draw index, b: triangle, a: 1 where covered, else all 0
};
struct PassCapture {
  std::string pass;      // the node's name
  std::string resource;  // the resource's name ("hdr", "depth", "bloom 1", "visibility buffer")
  CaptureContent content = CaptureContent::Color;
  ImageRGBA32F image;
};

// A declared node and the nodes whose outputs it reads (graph::dataInputs), by declaration index.
struct PassNode {
  std::string name;
  std::vector<uint32_t> inputs;
};

// Host work before the first frame (opening the workload), reported apart from GPU time.
struct StartupTimes {
  double sceneMs = 0.0;        // scene file, generation/import or the cooked cache
  double deviceMs = 0.0;       // Vulkan instance and device
  double uploadMs = 0.0;       // scene data to the GPU
  double pipelinesMs = 0.0;    // inside vkCreate*Pipelines (part of features/graph set-up)
  uint32_t pipelines = 0;
  std::string pipelineCache = "off";  // on-disk cache at start: off | cold | warm
  double graphMs = 0.0;        // features, frame-graph declaration and compilation
  double graphCompileMs = 0.0; // graph::compile() of the frame graph alone (part of graphMs)
};

enum class GraphDetail { Brief, Full };

class Workload {
 public:
  virtual ~Workload() = default;
  virtual const DeviceDescription& device() const = 0;
  // Renders one frame and returns its timings. Timestamps of frame N may be read back during a
  // later frame (no stall); the returned timings are always complete for the frame they describe.
  virtual FrameTiming renderFrame() = 0;
  // Waits for the GPU, returns timings of frames not yet returned (empty if none).
  virtual std::vector<FrameTiming> finish() = 0;
  // Calibration: renders one frame with each pass alone on an idle device, in the compiled order,
  // and returns its timings: each pass's isolated cost. Call after finish(). A workload that
  // cannot returns a timing without passes.
  virtual FrameTiming renderIsolatedFrame() { return {}; }
  // Critical-path shares: per declared pass (declaration order), how much shorter the frame's
  // longest chain through the compiled schedule (data edges, queue order, semaphore waits) would
  // be if the pass cost nothing, as a share of it, with `costMs` per pass (isolated costs). Empty
  // when the workload has no schedule.
  virtual std::vector<double> criticalPathShares(const std::vector<double>& costMs) const {
    (void)costMs;
    return {};
  }
  // render.async measured: how many queues the compiled frame graph runs on (1: every pass on the
  // graphics queue), and a switch that compiles the graph again with async compute on or off,
  // keeping the features, their resources and the per-frame state (particles, HiZ). Call after
  // finish(). A workload that cannot switch returns false.
  virtual uint32_t queuesUsed() const { return 1; }
  // Whether the render path draws the cooked clusters (debug.view=lod|clusters can show them).
  virtual bool drawsClusters() const { return false; }
  virtual bool setAsyncCompute(bool on) {
    (void)on;
    return false;
  }
  // The last frame's HDR image (before tone mapping) and the tone-mapped display image (linear
  // values in [0,1]; the PNG writer applies the sRGB curve).
  virtual ImageRGBA32F readHdr() = 0;
  virtual ImageRGBA32F readDisplay() = 0;
  virtual std::string graphviz(GraphDetail detail) const = 0;
  // Scene/run statistics: instances, instances_visible, triangles, triangles_visible, lights, ...
  virtual std::map<std::string, double> stats() const = 0;
  // Validation messages counted so far (0 when validation is off).
  virtual uint64_t validationMessages() const = 0;
  virtual StartupTimes startup() const { return {}; }
  // With --check-finite: one entry per checked pass, in execution order (the first bad one is where
  // a bad value was born); empty without the flag or when nothing writes float data.
  virtual std::vector<NonFiniteCounts> nonFiniteCounts() const { return {}; }
  // With --capture: the last rendered frame's captured images, in declaration order of their nodes.
  virtual std::vector<PassCapture> capturedPasses() { return {}; }
  // Every declared node with its data inputs, in declaration order (empty: no graph).
  virtual std::vector<PassNode> passGraph() const { return {}; }
};

// Opens the workload for a scene. Throws fgb::InputError (bad scene/option), fgb::DeviceError.
std::unique_ptr<Workload> openWorkload(const WorkloadConfig& config);

// The renderer's entries of the knob registry (render.*, lighting.*, bloom.*, debug.*, particles.*).
std::vector<KnobSpec> rendererKnobSpecs();

// Lists Vulkan devices (for `fgbench devices`). Throws fgb::DeviceError when Vulkan is unusable.
std::vector<DeviceDescription> listDevices();

}  // namespace fgb::render
