// VulkanGraph: a frame graph compiled for this device, ready to execute every frame without
// creating anything: transient resources bound into the aliasing heaps, barriers and rendering
// infos translated to Vulkan once, command buffers and query pools per frame in flight, one
// timeline semaphore per logical queue. Built in executable_graph.cpp, run by executor.cpp,
// timed by timestamps.cpp.
#pragma once

#include "barrier_batch.hpp"
#include "command_buffer.hpp"
#include "device.hpp"
#include "spin.hpp"

#include <fgb/graph/compiler.hpp>
#include <fgb/rhi/device.hpp>

#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace fgb::vulkan {

class VulkanGraph final : public rhi::ExecutableGraph {
 public:
  VulkanGraph(VulkanDevice& device, graph::FrameGraph&& graph, const rhi::GraphOptions& options);
  ~VulkanGraph() override;

  const graph::FrameGraph& declaration() const override { return declaration_; }
  const graph::CompiledGraph& compiled() const override { return compiled_; }
  uint64_t executions() const override { return executions_; }
  HostTimes lastHostTimes() const override { return hostTimes_; }
  std::vector<rhi::GraphTimings> takeTimings() override;
  rhi::BufferId buffer(uint32_t resource) const override { return buffers_.at(resource); }
  rhi::TextureId texture(uint32_t resource) const override { return textures_.at(resource); }

  // executor.cpp
  uint64_t submit(rhi::RunMode mode);  // returns the execution index
  [[nodiscard]] bool isComplete(uint64_t execution) const;
  void waitFor(uint64_t execution) const;
  void waitForAll() const;
  [[nodiscard]] uint32_t id() const { return id_; }
  [[nodiscard]] const std::vector<TimelinePoint>& lastPoints() const { return lastPoints_; }
  // The primary command buffer of `step` (a compiled step) as the latest execution submitted it;
  // null when the step recorded nothing. Steps can so be submitted one by one (pass calibration).
  [[nodiscard]] VkCommandBuffer stepCommandBuffer(uint32_t step) const;

  // Used by the job context.
  [[nodiscard]] rhi::BufferId bufferOf(graph::BufferHandle handle) const;
  [[nodiscard]] rhi::TextureId textureOf(graph::TextureHandle handle) const;

 private:
  // A translated barrier (in imageBarriers_ or bufferBarriers_) as a step uses it.
  struct BarrierRef {
    uint32_t resource = 0;
    uint32_t index = 0;  // into imageBarriers_ or bufferBarriers_
    uint32_t heap = graph::kInvalidIndex;  // graph-owned memory it protects; none for imports
    bool image = false;
    bool elidable = false;  // may be skipped while no recorded command has touched its heap
  };
  struct BarrierList {
    uint32_t first = 0;  // into barrierRefs_
    uint32_t count = 0;
  };
  struct Step {
    uint32_t node = 0;
    graph::NodeType type = graph::NodeType::Graphics;
    uint32_t logicalQueue = 0;
    BarrierList before;
    BarrierList after;
    uint32_t firstHeap = 0;  // into stepHeaps_: heaps of the graph-owned resources the node uses
    uint32_t heapCount = 0;
    bool rendering = false;
    VkRenderingInfo renderingInfo = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    graph::Extent extent{};
    bool lastOfSubmit = false;  // the submit's remaining barriers are recorded at its end
    uint64_t staticKey = 0;     // what the graph fixes about the step's recording (hashStaticKeys)
  };
  // Per frame in flight. Every step has a primary command buffer, kept from one execution of the
  // slot to the next. Recorded per node, a step's buffer is recorded again only when the step's key
  // changed (stepKey), else submitted as it is; recorded as blocks, the first step's buffer holds
  // the whole submit's commands, recorded again when any of its steps' keys changed.
  struct Slot {
    std::vector<Owned<VkCommandPool>> pools;      // per logical queue (buffers reset one by one)
    std::vector<VkCommandBuffer> commandBuffers;  // per step
    std::vector<uint8_t> recorded;                // per step: the buffer holds commands (else it is not submitted)
    std::vector<uint8_t> started;                 // per step: the node's prologue ran (it did work; see endStep)
    std::vector<uint64_t> keys;                   // per step: the key the buffer was recorded under
    std::vector<uint8_t> reusable;                // per step: keys[step] is valid (the step has a key)
    Owned<VkQueryPool> queries;
    uint64_t execution = 0;
    bool pending = false;
    bool timed = false;  // timings not yet read
    uint32_t spinIterations = 0;  // debug.slow_pass: what this execution's spin ran
    bool blocks = false;          // the kept buffers hold blocks (one per submit), not nodes
  };

  // executable_graph.cpp
  graph::CompileOptions compileOptions();
  void release();  // unregisters, destroys the transients, frees the heaps
  void mapQueues(uint32_t requested, bool separate);
  std::vector<rhi::TextureUsage> textureUsages() const;
  std::vector<rhi::BufferUsage> bufferUsages() const;
  void createResources();
  void translateBarriers();
  void listTouchedHeaps();
  void translateRendering();
  void orderSubmits();
  void createSyncAndSlots();
  void createScopedSets();
  void createSpin();
  void hashStaticKeys();
  // executor.cpp
  void runNodeBuffers(Slot& slot, const graph::Submit& submit, uint64_t execution);
  void runBlock(Slot& slot, const graph::Submit& submit, uint64_t execution);
  void beginBuffer(uint32_t bufferStep, VkCommandBufferUsageFlags usage);
  void endBuffer(Slot& slot);
  [[nodiscard]] bool keyOf(uint32_t stepIndex, uint64_t& key) const;
  [[nodiscard]] uint64_t stepKey(uint32_t stepIndex, uint64_t userKey) const;
  void recordStep(Slot& slot, uint32_t stepIndex, uint64_t execution);
  void replayStep(const Slot& slot, uint32_t stepIndex);
  VkCommandBuffer commandBufferForRecording();
  void beginStep();  // the deferred prologue of the step being recorded
  void endStep(bool recorded);
  void markHeapsTouched(const Step& step);
  void queueBarriers(BarrierList list);
  void flushBarriers();  // records the queued barriers into the step's buffer (replaying: drops them)
  void submitAll(const Slot& slot, uint64_t execution, rhi::RunMode mode);
  // RunMode::Isolated (isolated.cpp): one node per submit, each waited for before the next.
  void submitIsolated(const Slot& slot, uint64_t execution);
  void finishSubmission(uint64_t execution, rhi::RunMode mode);
  uint64_t timelineBase(uint64_t execution) const { return (execution + 1) * valuesPerExecution_; }
  // timestamps.cpp
  void collectTimings(Slot& slot);
  void collectFinishedTimings();

  VulkanDevice& device_;
  uint32_t id_;
  rhi::GraphOptions options_;
  graph::FrameGraph declaration_;
  graph::CompiledGraph compiled_;
  std::vector<graph::Job> jobs_;  // per node, moved out of the declaration
  std::vector<graph::RecordingKey> recordingKeys_;  // per node, moved out of the declaration

  uint32_t logicalQueues_ = 1;
  std::vector<uint32_t> deviceQueueOf_;     // per logical queue
  std::array<uint32_t, graph::kQueueClassCount> logicalOfClass_{0, 0, 0};
  std::vector<uint64_t> timestampMask_;     // per logical queue; 0: no timestamps there
  std::vector<rhi::BufferId> buffers_;      // per resource
  std::vector<rhi::TextureId> textures_;    // per resource
  std::vector<bool> ownsResource_;          // transient: created (and destroyed) by this graph
  std::vector<Allocation> heaps_;
  std::unique_ptr<ScopedSets> scopedSets_;  // per step (bindless devices); else the shared set

  std::vector<Step> steps_;
  std::vector<VkImageMemoryBarrier2> imageBarriers_;
  std::vector<VkBufferMemoryBarrier2> bufferBarriers_;
  std::vector<BarrierRef> barrierRefs_;
  std::vector<uint32_t> stepHeaps_;
  std::vector<VkRenderingAttachmentInfo> attachments_;
  std::vector<uint32_t> submitOrder_;
  std::vector<Owned<VkSemaphore>> timelines_;  // per logical queue
  uint64_t valuesPerExecution_ = 1;
  std::vector<Slot> slots_;
  uint32_t queryCount_ = 0;         // per slot: two per step, plus where the slow node's own work ends
  std::unique_ptr<SpinWork> spin_;  // debug.slow_pass
  uint32_t slowStep_ = graph::kInvalidIndex;
  uint64_t executions_ = 0;
  HostTimes hostTimes_;
  std::vector<TimelinePoint> lastPoints_;  // completion points of the latest execution
  std::deque<rhi::GraphTimings> timings_;
  VulkanCommandBuffer commandBuffer_;

  // Recording state of the current execution (executor.cpp).
  struct Recording {
    Slot* slot = nullptr;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // the buffer being recorded, begun lazily: commandBufferForRecording()
    VkCommandBufferUsageFlags usage = 0;   // one-time submit unless the buffer may be kept
    VkQueryPool queries = VK_NULL_HANDLE;
    uint32_t step = 0;
    uint32_t bufferStep = 0;  // whose buffer in Slot::commandBuffers: the step's, or its block's first step's
  } recording_;
  BarrierBatch pendingBarriers_;
  // Hash of the barrier references queued into pendingBarriers_ since it was last emptied: with the
  // elision state, all that decides which barriers a step's buffer begins (and ends) with.
  uint64_t pendingSignature_ = 0;
  bool replaying_ = false;            // host state follows a kept buffer: barriers are dropped, not recorded
  std::vector<uint8_t> heapTouched_;  // per heap: a submitted command used it in this execution
  std::vector<uint8_t> heapTouchedAtBlock_;  // heapTouched_ where the current block began (runBlock)
  uint32_t stepsRecorded_ = 0;        // in the current execution
  uint32_t stepsReused_ = 0;

  // Scratch for submission, reused every execution (no per-frame allocation once warm).
  std::vector<VkSubmitInfo2> submitInfos_;
  std::vector<VkSemaphoreSubmitInfo> waitInfos_;
  std::vector<VkSemaphoreSubmitInfo> signalInfos_;
  std::vector<VkCommandBufferSubmitInfo> commandInfos_;
};

}  // namespace fgb::vulkan
