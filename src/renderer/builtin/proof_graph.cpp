// The proof scene's settings, device objects and frame graph.
#include "proof_workload.hpp"

#include <fgb/core/error.hpp>
#include <fgb/graph/format.hpp>
#include <fgb/rhi/job_context.hpp>

#include <charconv>
#include <cstdio>
#include <string>

namespace fgb::render {
namespace {

constexpr graph::Format kHdrFormat = graph::Format::R16G16B16A16Sfloat;
constexpr graph::Format kDisplayFormat = graph::Format::R8G8B8A8Srgb;
constexpr uint32_t kVertexBytes = 32;  // vec4 position + vec4 colour

template <class T>
T parseKnob(const std::string& key, const std::string& value) {
  T result{};
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), result);
  if (error != std::errc() || end != value.data() + value.size()) {
    throw InputError("builtin:proof: --set " + key + "=" + value + ": not a number");
  }
  return result;
}

struct PatternPush {
  uint32_t vertexBuffer;
  uint32_t triangleCount;
  float time;
};
struct TonemapPush {
  uint32_t hdrTexture;
  uint32_t sampler;
  float exposure;
};
struct LuminancePush {
  uint32_t hdrTexture;
  uint32_t outputBuffer;
  uint32_t width;
  uint32_t height;
};

// Readback buffers: written by the transfer node, read by the host after the frame.
constexpr graph::ImportState kHostReadState{graph::kStageHost, graph::kAccessHostRead, graph::Layout::Undefined,
                                            graph::QueueClass::Transfer};

}  // namespace

ProofSettings proofSettings(const WorkloadConfig& config, uint32_t deviceSampleCounts) {
  ProofSettings s;
  if (config.width) s.width = config.width;
  if (config.height) s.height = config.height;
  if (config.msaa) s.msaa = config.msaa;
  if (s.msaa != 1 && s.msaa != 2 && s.msaa != 4 && s.msaa != 8) {
    throw InputError("--msaa " + std::to_string(s.msaa) + ": expected 1, 2, 4 or 8");
  }
  // Clamped to the nearest supported count not above the request (lavapipe: {1, 4}).
  if (const uint32_t supported = rhi::clampSampleCount(s.msaa, deviceSampleCounts); supported != s.msaa) {
    std::fprintf(stderr, "fgbench: warning: --msaa %u not supported by the device; using %u\n", s.msaa, supported);
    s.msaa = supported;
  }
  for (const auto& [key, value] : config.knobs) {
    if (key == "exposure") s.exposure = parseKnob<float>(key, value);
    else if (key == "triangles") s.triangles = parseKnob<uint32_t>(key, value);
    else if (key == "speed") s.speed = parseKnob<float>(key, value);
    else if (key == "queues") s.queues = parseKnob<uint32_t>(key, value);
    else if (key == "separate-queues") s.separateQueues = parseKnob<uint32_t>(key, value) != 0;
    else throw InputError("builtin:proof: unknown knob '" + key +
                          "' (known: exposure, triangles, speed, queues, separate-queues)");
  }
  if (s.triangles < 2 || s.triangles > 100000) throw InputError("builtin:proof: triangles must be in [2, 100000]");
  if (s.queues > 3) throw InputError("builtin:proof: queues must be 0..3");
  return s;
}

ProofResources createProofResources(rhi::Device& device, const ProofSettings& settings) {
  ProofResources r;
  r.pattern = device.createComputePipeline({"Pattern", "proof/pattern.comp"});
  r.luminance = device.createComputePipeline({"Debug luminance", "proof/luminance.comp"});
  rhi::GraphicsPipelineDesc draw;
  draw.name = "Draw pattern";
  draw.vertexShader = "proof/scene.vert";
  draw.fragmentShader = "proof/scene.frag";
  draw.vertexBindings = {{0, kVertexBytes, false}};
  draw.vertexAttributes = {{0, 0, rhi::VertexFormat::R32G32B32A32Sfloat, 0}, {1, 0, rhi::VertexFormat::R32G32B32A32Sfloat, 16}};
  draw.colorFormats = {kHdrFormat};
  draw.samples = settings.msaa;
  r.draw = device.createGraphicsPipeline(draw);
  rhi::GraphicsPipelineDesc tonemap;
  tonemap.name = "Tone map";
  tonemap.vertexShader = "common/fullscreen.vert";
  tonemap.fragmentShader = "proof/tonemap.frag";
  tonemap.colorFormats = {kDisplayFormat};
  r.tonemap = device.createGraphicsPipeline(tonemap);
  r.pointSampler = device.createSampler({"point clamp", rhi::Filter::Nearest, rhi::Filter::Nearest, rhi::Filter::Nearest,
                                         rhi::AddressMode::ClampToEdge});
  r.pointSamplerIndex = device.samplerIndex(r.pointSampler);
  const uint64_t pixels = uint64_t{settings.width} * settings.height;
  r.hdrReadback = device.createBuffer(
      {"HDR readback", pixels * graph::bytesPerPixel(kHdrFormat), rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  r.displayReadback = device.createBuffer(
      {"Display readback", pixels * graph::bytesPerPixel(kDisplayFormat), rhi::kBufferTransferDst, rhi::MemoryUsage::Readback});
  return r;
}

graph::FrameGraph buildProofGraph(const ProofSettings& s, const ProofResources& r) {
  using namespace graph;
  FrameGraph g;
  const Extent extent{s.width, s.height, 1};
  const uint64_t pixels = uint64_t{s.width} * s.height;

  BufferHandle vertices = g.createBuffer("Pattern vertices", {uint64_t{s.triangles} * 3 * kVertexBytes});
  TextureHandle hdr = g.createTexture("HDR colour", {kHdrFormat, extent});
  TextureHandle display = g.createTexture("Display", {kDisplayFormat, extent});
  BufferHandle hdrReadback = g.importBuffer("HDR readback", {pixels * bytesPerPixel(kHdrFormat)}, rhi::external(r.hdrReadback),
                                            kHostReadState, kHostReadState);
  BufferHandle displayReadback = g.importBuffer("Display readback", {pixels * bytesPerPixel(kDisplayFormat)},
                                                rhi::external(r.displayReadback), kHostReadState, kHostReadState);

  {
    auto node = g.addNode("Pattern", NodeType::Compute);
    vertices = node.write(vertices, Access::StorageWrite);
    node.setJob([=, triangles = s.triangles, speed = s.speed](JobContext& context) {
      auto& ctx = rhi::rhiContext(context);
      ctx.cmd().bindPipeline(r.pattern);
      ctx.cmd().push(PatternPush{ctx.storageBufferIndex(vertices), triangles, speed * static_cast<float>(ctx.execution())});
      ctx.cmd().dispatch((triangles + 63) / 64);
    });
  }
  {
    auto node = g.addNode("Draw pattern", NodeType::Graphics);
    node.read(vertices, Access::Vertex);
    const ClearValue background{{0.02f, 0.02f, 0.05f, 1.0f}};
    if (s.msaa > 1) {
      const TextureHandle multisampled = g.createTexture("HDR colour MSAA", {kHdrFormat, extent, 1, 1, s.msaa});
      hdr = node.addColorTargetWithResolve(multisampled, hdr, nullptr, LoadOp::Clear, background);
    } else {
      hdr = node.addColorTarget(hdr, LoadOp::Clear, background);
    }
    node.setJob([=, triangles = s.triangles](JobContext& context) {
      auto& ctx = rhi::rhiContext(context);
      ctx.cmd().bindPipeline(r.draw);
      ctx.cmd().bindVertexBuffer(0, ctx.buffer(vertices));
      ctx.cmd().draw(triangles * 3);
    });
  }
  {
    auto node = g.addNode("Tone map", NodeType::Graphics);
    node.read(hdr, Access::Sampled, kStageFragmentShader);
    display = node.addColorTarget(display, LoadOp::DontCare);
    node.setJob([=, exposure = s.exposure](JobContext& context) {
      auto& ctx = rhi::rhiContext(context);
      ctx.cmd().bindPipeline(r.tonemap);
      ctx.cmd().push(TonemapPush{ctx.sampledTextureIndex(hdr), r.pointSamplerIndex, exposure});
      ctx.cmd().draw(3);
    });
  }
  {
    auto node = g.addNode("Readback", NodeType::Transfer);
    node.sideEffect();
    node.read(hdr, Access::TransferSrc);
    node.read(display, Access::TransferSrc);
    hdrReadback = node.write(hdrReadback, Access::TransferDst);
    displayReadback = node.write(displayReadback, Access::TransferDst);
    node.setJob([=](JobContext& context) {
      auto& ctx = rhi::rhiContext(context);
      ctx.cmd().copyTextureToBuffer(ctx.texture(hdr), ctx.buffer(hdrReadback));
      ctx.cmd().copyTextureToBuffer(ctx.texture(display), ctx.buffer(displayReadback));
    });
  }
  {
    // Declared like any debug view, but nothing reads its output: culled, costs nothing.
    BufferHandle luminance = g.createBuffer("Luminance", {pixels * 4});
    auto node = g.addNode("Debug luminance", NodeType::Compute);
    node.read(hdr, Access::Sampled);
    luminance = node.write(luminance, Access::StorageWrite);
    node.setJob([=, width = s.width, height = s.height](JobContext& context) {
      auto& ctx = rhi::rhiContext(context);
      ctx.cmd().bindPipeline(r.luminance);
      ctx.cmd().push(LuminancePush{ctx.sampledTextureIndex(hdr), ctx.storageBufferIndex(luminance), width, height});
      ctx.cmd().dispatch((width + 7) / 8, (height + 7) / 8);
    });
  }
  return g;
}

}  // namespace fgb::render
