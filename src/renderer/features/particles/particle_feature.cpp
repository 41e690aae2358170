#include "particle_feature.hpp"

#include "../context/render_space.hpp"

#include <fgb/rhi/job_context.hpp>
#include <fgb/rhi/upload.hpp>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <numeric>
#include <span>

#include "renderer/shared/particles.h"

namespace fgb::features {
namespace {

using graph::Access;

constexpr uint64_t kArgsBytes = sizeof(gpu::DrawCommand);

// Particle state persists across frames. Import states name the stages and accesses of the use
// that comes before (initial) and after (final) the graph; the queue classes document where those
// uses run (buffers are shared by every queue family, so no ownership changes hands).
constexpr graph::ImportState kFreeListState{graph::kStageComputeShader,
                                            graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
                                            graph::Layout::Undefined, graph::QueueClass::Compute};
constexpr graph::ImportState kPoolInitial{graph::kStageVertexShader, graph::kAccessShaderStorageRead,
                                          graph::Layout::Undefined, graph::QueueClass::Graphics};
constexpr graph::ImportState kPoolFinal{graph::kStageComputeShader,
                                        graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite,
                                        graph::Layout::Undefined, graph::QueueClass::Compute};

// Emitters (and so the particles they spawn) live in the particles' render space
// (RenderSpace::ofParticles); each frame draws them moved into its own.
gpu::Emitter toGpu(const scene::Emitter& e, const RenderSpace& space, uint32_t seedOffset) {
  gpu::Emitter out{};
  out.positionRate = glm::vec4(space.point(e.position), e.rate);
  out.directionCone = glm::vec4(glm::normalize(e.direction), std::cos(glm::radians(e.coneAngleDeg)));
  out.colorStart = e.colorStart;
  out.colorEnd = e.colorEnd;
  out.speedSize = {e.speedMin, e.speedMax, e.sizeStart, e.sizeEnd};
  out.lifetime = {e.lifetime, 0.0f, 0.0f, 0.0f};
  out.seed = {e.seed + seedOffset, 0u, 0u, 0u};
  return out;
}

template <class T>
std::span<const std::byte> bytesOf(const std::vector<T>& values) {
  return std::as_bytes(std::span(values));
}

}  // namespace

void ParticleFeature::configure(const GpuScene& scene) {
  poolSize_ = 0;
  for (const auto& emitter : scene.scene->emitters) poolSize_ += emitter.maxParticles;
  emitterCount_ = uint32_t(scene.scene->emitters.size());
}

void ParticleFeature::createState(rhi::Device& device, const scene::Scene& scene, uint32_t seedOffset) {
  auto storage = [&](const char* name, uint64_t size, rhi::BufferUsage extra = 0) {
    return device.createBuffer({name, size, rhi::kBufferStorage | rhi::kBufferTransferDst | extra, rhi::MemoryUsage::DeviceLocal});
  };
  pool_ = storage("particle pool", sizeof(gpu::Particle) * poolSize_);
  freeList_ = storage("particle free list", uint64_t{4} * (poolSize_ + 1));
  emitters_ = storage("particle emitters", sizeof(gpu::Emitter) * emitterCount_);
  quadIndices_ = device.createBuffer({"particle quad", 24, rhi::kBufferIndex | rhi::kBufferTransferDst, rhi::MemoryUsage::DeviceLocal});
  argsTemplate_ = storage("particle draw template", kArgsBytes, rhi::kBufferTransferSrc);

  std::vector<uint32_t> freeList{poolSize_};  // [0]: count, then every slot
  freeList.resize(size_t{poolSize_} + 1);
  std::iota(freeList.begin() + 1, freeList.end(), 0u);
  std::vector<gpu::Emitter> emitters;
  const RenderSpace space = RenderSpace::ofParticles(scene);
  for (const auto& emitter : scene.emitters) emitters.push_back(toGpu(emitter, space, seedOffset));
  rhi::uploadBuffer(device, pool_, bytesOf(std::vector<gpu::Particle>(poolSize_)));
  rhi::uploadBuffer(device, freeList_, bytesOf(freeList));
  rhi::uploadBuffer(device, emitters_, bytesOf(emitters));
  rhi::uploadBuffer(device, quadIndices_, bytesOf(std::vector<uint32_t>{0, 1, 2, 2, 1, 3}));
  rhi::uploadBuffer(device, argsTemplate_, bytesOf(std::vector<gpu::DrawCommand>{{6, 0, 0, 0, 0}}));
}

void ParticleFeature::initialize(FeatureInit& init) {
  configure(init.scene);
  device_ = &init.device;
  scene_ = &init.scene;
  if (!enabled()) return;
  createState(init.device, *init.scene.scene, init.settings.particleSeedOffset);
  emitPipeline_ = init.device.createComputePipeline({"particle emit", "renderer/particle_emit.comp"});
  updatePipeline_ = init.device.createComputePipeline({"particle update", "renderer/particle_update.comp"});
  rhi::GraphicsPipelineDesc desc;
  desc.name = "particle render";
  desc.vertexShader = "renderer/particle.vert";
  desc.fragmentShader = "renderer/particle.frag";
  desc.colorFormats = {kHdrFormat};
  desc.blend = {rhi::BlendMode::Alpha};
  depthTest_ = init.path.depthTest;
  setDepthState(desc, depthTest_, false);
  desc.samples = init.settings.msaa;
  renderPipeline_ = init.device.createGraphicsPipeline(desc);
}

void ParticleFeature::declare(graph::FrameGraph& graph, Blackboard& board) {
  if (!enabled()) return;
  auto pool = graph.importBuffer("particle pool", {sizeof(gpu::Particle) * poolSize_, {}}, rhi::external(pool_),
                                 kPoolInitial, kPoolFinal);
  auto freeList = graph.importBuffer("particle free list", {uint64_t{4} * (poolSize_ + 1), {}}, rhi::external(freeList_),
                                     kFreeListState, kFreeListState);
  auto args = graph.createBuffer("particle draw args", {kArgsBytes, {}});
  auto alive = graph.createBuffer("alive particles", {uint64_t{4} * poolSize_, {}});

  auto reset = graph.addNode("Particle Reset", graph::NodeType::Transfer);
  args = reset.write(args, Access::TransferDst);
  reset.setJob([templ = argsTemplate_, args](graph::JobContext& context) {
    auto& ctx = rhi::rhiContext(context);
    ctx.cmd().copyBuffer(templ, ctx.buffer(args), kArgsBytes);
  });
  reset.recordingFixed();

  auto emit = graph.addNode("Particle Emit", graph::NodeType::Compute);
  pool = emit.write(pool, Access::StorageReadWrite);
  freeList = emit.write(freeList, Access::StorageReadWrite);
  const gpu::ParticleEmitPush emitPush{device_->storageBufferIndex(emitters_), device_->storageBufferIndex(pool_),
                                       device_->storageBufferIndex(freeList_), 0};
  emit.setJob([push = emitPush, pipeline = emitPipeline_, emitters = emitterCount_,
               scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.frame = scene->frame(ctx.execution()).constantsIndex;  // the simulation step and its index
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().dispatch(emitters);
  });
  emit.recordingFixed();  // the step and the time step come from the frame's constants

  auto update = graph.addNode("Particle Update", graph::NodeType::Compute);
  pool = update.write(pool, Access::StorageReadWrite);
  freeList = update.write(freeList, Access::StorageReadWrite);
  args = update.write(args, Access::StorageReadWrite);
  alive = update.write(alive, Access::StorageWrite);
  gpu::ParticleUpdatePush updatePush{device_->storageBufferIndex(pool_), device_->storageBufferIndex(freeList_), 0, 0,
                                     poolSize_, 0};
  update.setJob([push = updatePush, pipeline = updatePipeline_, args, alive,
                 scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.frame = scene->frame(ctx.execution()).constantsIndex;  // the simulation step
    push.drawArgs = ctx.storageBufferIndex(args);
    push.aliveList = ctx.storageBufferIndex(alive);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().dispatch((push.poolSize + FGB_PARTICLE_GROUP_SIZE - 1) / FGB_PARTICLE_GROUP_SIZE);
  });
  update.recordingFixed();

  auto& targets = board.get<FrameTargets>();
  auto render = addForwardPass(graph, targets, "Particle Render", false, depthTest_);
  render.read(args, Access::Indirect);
  // Storage buffers are visible per descriptor binding, not per stage: particle.vert reads these
  // through the read-only binding that particle.frag reads the opaque depth through, so both
  // stages are declared (synchronization validation checks each read against the barriers' stages).
  constexpr graph::StageMask kRenderStages = graph::kStageVertexShader | graph::kStageFragmentShader;
  render.read(alive, Access::StorageRead, kRenderStages);
  render.read(pool, Access::StorageRead, kRenderStages);
  gpu::ParticleRenderPush renderPush{0,
                                     device_->storageBufferIndex(pool_),
                                     device_->storageBufferIndex(emitters_),
                                     0,
                                     {}};
  render.setJob([push = renderPush, pipeline = renderPipeline_, quad = quadIndices_, args, alive,
                 opaqueDepth = opaqueDepthSource(targets, depthTest_), scene = scene_](graph::JobContext& context) mutable {
    auto& ctx = rhi::rhiContext(context);
    push.frame = scene->frame(ctx.execution()).constantsIndex;
    push.aliveList = ctx.storageBufferIndex(alive);
    push.opaqueDepth = opaqueDepth.push(ctx);
    ctx.cmd().bindPipeline(pipeline);
    ctx.cmd().push(push);
    ctx.cmd().bindIndexBuffer(quad, 0, rhi::IndexType::Uint32);
    ctx.cmd().drawIndexedIndirect(ctx.buffer(args), 0, 1, sizeof(gpu::DrawCommand));
  });
  render.recordingFixed();
}

void ParticleFeature::addStats(std::map<std::string, double>& stats) const {
  stats["particle_pool"] = poolSize_;
}

}  // namespace fgb::features
