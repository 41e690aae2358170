// Running compiled graphs: record every step in order (barriers, debug label, timestamps, dynamic
// rendering, the node's job; all but the job deferred until the job's first command, so nodes that
// record nothing cost nothing) into one command buffer per submit (a block) or per node, or submit
// the kept buffer again when the recording keys of its steps are unchanged; submit per the plan
// with one timeline semaphore per logical queue, and chain executions — of the same graph (frames
// in flight) and of sequential graphs.
#include "executable_graph.hpp"
#include "translate.hpp"

#include <fgb/core/error.hpp>
#include <fgb/rhi/job_context.hpp>

#include <algorithm>
#include <chrono>

namespace fgb::vulkan {
namespace {

class VulkanJobContext final : public rhi::JobContext {
 public:
  VulkanJobContext(const VulkanGraph& graph, const VulkanDevice& device, VulkanCommandBuffer& cmd, uint64_t execution)
      : graph_(graph), device_(device), cmd_(cmd), execution_(execution) {}

  void setExtent(graph::Extent extent) { extent_ = extent; }

  rhi::CommandBuffer& cmd() override { return cmd_; }
  rhi::BufferId buffer(graph::BufferHandle handle) const override { return graph_.bufferOf(handle); }
  rhi::TextureId texture(graph::TextureHandle handle) const override { return graph_.textureOf(handle); }
  uint32_t storageBufferIndex(graph::BufferHandle handle) const override {
    return device_.storageBufferIndex(graph_.bufferOf(handle));
  }
  uint32_t sampledTextureIndex(graph::TextureHandle handle) const override {
    return device_.sampledTextureIndex(graph_.textureOf(handle));
  }
  uint32_t storageTextureIndex(graph::TextureHandle handle) const override {
    return device_.storageTextureIndex(graph_.textureOf(handle));
  }
  uint32_t sampledGeneralTextureIndex(graph::TextureHandle handle) const override {
    return device_.texture(graph_.textureOf(handle)).sampledGeneralIndex;
  }
  uint64_t execution() const override { return execution_; }
  graph::Extent renderExtent() const override { return extent_; }

 private:
  const VulkanGraph& graph_;
  const VulkanDevice& device_;
  VulkanCommandBuffer& cmd_;
  uint64_t execution_;
  graph::Extent extent_{1, 1, 1};
};

constexpr auto mix = graph::hashCombine;

VkPipelineStageFlags2 waitStages(graph::StageMask stages) {
  const VkPipelineStageFlags2 vk = toVkStages(stages);
  return vk == VK_PIPELINE_STAGE_2_NONE ? VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT : vk;
}

// Label colours by node type, as RenderDoc and friends show them.
constexpr float kLabelColors[3][4] = {
    {0.95f, 0.55f, 0.15f, 1.0f},  // graphics: orange
    {0.25f, 0.55f, 0.95f, 1.0f},  // compute: blue
    {0.30f, 0.80f, 0.35f, 1.0f},  // transfer: green
};

}  // namespace

uint64_t VulkanGraph::submit(rhi::RunMode mode) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const uint64_t execution = executions_;
  Slot& slot = slots_[execution % slots_.size()];
  if (slot.pending) {
    // Every frame in flight is still in use: wait for the oldest (the only stall, by design).
    waitFor(slot.execution);
    collectTimings(slot);
  }
  collectFinishedTimings();  // earlier executions that completed meanwhile: no waiting
  // Kept command buffers write the same queries again: reset them on the host, as every execution.
  if (slot.queries) vkResetQueryPool(device_.device(), slot.queries.get(), 0, queryCount_);
  // Reading query results and resetting queries can still block on lavapipe (it takes the queue's
  // context while the queue runs the previous frame: 0.1 ms and more for 1,000 queries), so that counts
  // as throttling, not as the frame's recording.
  const auto unblocked = Clock::now();

  std::fill(heapTouched_.begin(), heapTouched_.end(), 0);
  stepsRecorded_ = stepsReused_ = 0;
  const bool blocks = !options_.nodeBuffers && mode != rhi::RunMode::Isolated;
  if (slot.blocks != blocks) {  // the kept buffers hold the other layout: record everything
    std::fill(slot.reusable.begin(), slot.reusable.end(), 0);
    std::fill(slot.recorded.begin(), slot.recorded.end(), 0);
    slot.blocks = blocks;
  }
  recording_.slot = &slot;
  recording_.queries = slot.queries.get();
  for (const graph::Submit& s : compiled_.submits) {
    if (blocks)
      runBlock(slot, s, execution);
    else
      runNodeBuffers(slot, s, execution);
  }
  const auto recorded = Clock::now();
  if (mode == rhi::RunMode::Isolated) {
    submitIsolated(slot, execution);
  } else {
    submitAll(slot, execution, mode);
  }

  slot.execution = execution;
  slot.pending = true;
  slot.timed = static_cast<bool>(slot.queries);
  ++executions_;
  const auto milliseconds = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  hostTimes_ = {milliseconds(unblocked - start), milliseconds(recorded - unblocked),
                milliseconds(Clock::now() - recorded), stepsRecorded_, stepsReused_};
  return execution;
}

// Each step of the submit is recorded into its own buffer, or its kept buffer is reused. Host
// state (queued barriers, touched heaps) moves on the same way either way, so the next step's key
// sees what its commands would be.
void VulkanGraph::runNodeBuffers(Slot& slot, const graph::Submit& submit, uint64_t execution) {
  for (uint32_t s = submit.firstStep; s < submit.firstStep + submit.stepCount; ++s) {
    uint64_t key = 0;
    const bool keyed = keyOf(s, key);
    if (keyed && slot.reusable[s] && slot.keys[s] == key) {
      replayStep(slot, s);
      ++stepsReused_;
      continue;
    }
    beginBuffer(s, keyed ? 0 : VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT);
    recordStep(slot, s, execution);
    endBuffer(slot);
    slot.keys[s] = key;
    slot.reusable[s] = keyed;
    ++stepsRecorded_;
  }
}

// The submit's steps share one buffer (a block), reused while every step's key is unchanged. A
// step's key depends on the host state the steps before it leave, so keys are checked as the steps
// replay; at the first changed one the host state goes back to where the block began and the
// whole block records. The previous submit's last step flushed its barriers, so at a block's start
// nothing is queued: only the touched heaps need putting back.
void VulkanGraph::runBlock(Slot& slot, const graph::Submit& submit, uint64_t execution) {
  const uint32_t first = submit.firstStep;
  const uint32_t end = first + submit.stepCount;
  if (!pendingBarriers_.empty()) throw DeviceError("internal: barriers queued across a submit boundary");
  heapTouchedAtBlock_.assign(heapTouched_.begin(), heapTouched_.end());
  uint32_t s = first;
  for (uint64_t key = 0; s < end && keyOf(s, key) && slot.reusable[s] && slot.keys[s] == key; ++s) replayStep(slot, s);
  if (s == end) {
    stepsReused_ += submit.stepCount;
    return;
  }
  heapTouched_.assign(heapTouchedAtBlock_.begin(), heapTouchedAtBlock_.end());
  pendingBarriers_.clear();
  pendingSignature_ = 0;
  beginBuffer(first, options_.recordEveryFrame ? VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT : 0);
  for (s = first; s < end; ++s) {
    slot.reusable[s] = keyOf(s, slot.keys[s]);
    recordStep(slot, s, execution);
  }
  endBuffer(slot);
  stepsRecorded_ += submit.stepCount;
}

// Steps recorded from here on go into the buffer of step `bufferStep`, begun at its first command.
void VulkanGraph::beginBuffer(uint32_t bufferStep, VkCommandBufferUsageFlags usage) {
  recording_.cmd = VK_NULL_HANDLE;
  recording_.bufferStep = bufferStep;
  recording_.usage = usage;
}

// Ends the buffer begun by beginBuffer; only a buffer that holds commands is submitted.
void VulkanGraph::endBuffer(Slot& slot) {
  if (recording_.cmd != VK_NULL_HANDLE) {
    check(vkEndCommandBuffer(recording_.cmd), "vkEndCommandBuffer");
    slot.recorded[recording_.bufferStep] = 1;
  }
  recording_.cmd = VK_NULL_HANDLE;
}

// False when the step must be recorded whatever happened before: its node declared no key
// (NodeBuilder::recordingDependsOn), or debug.record_every_frame is on. Else `key` is its key now.
bool VulkanGraph::keyOf(uint32_t stepIndex, uint64_t& key) const {
  const graph::RecordingKey& userKey = recordingKeys_[steps_[stepIndex].node];
  if (options_.recordEveryFrame || !userKey) return false;
  key = stepKey(stepIndex, userKey());
  return true;
}

// A step's commands are a function of: its job (the node's key), what the graph fixes (resources,
// extent, query indices, labels: staticKey), the barriers queued before it (pendingSignature_),
// which of its barriers are elided (heapTouched_ of their heaps, which depends on whether earlier
// steps did work) and the slow-pass spin's iterations (calibrated over the first executions).
uint64_t VulkanGraph::stepKey(uint32_t stepIndex, uint64_t userKey) const {
  const Step& step = steps_[stepIndex];
  uint64_t key = mix(mix(step.staticKey, userKey), pendingSignature_);
  for (const BarrierList list : {step.before, step.after}) {
    for (uint32_t i = list.first; i < list.first + list.count; ++i) {
      const BarrierRef& ref = barrierRefs_[i];
      if (ref.elidable) key = mix(key, heapTouched_[ref.heap]);
    }
  }
  if (stepIndex == slowStep_) key = mix(key, spin_->iterations());
  return key;
}

// Records the step into the buffer beginBuffer named, which is begun only when something is
// recorded into it: a buffer of steps that record nothing is not submitted (their barriers move on
// to the next step that records; the submit's semaphore wait and signal still order the queues).
void VulkanGraph::recordStep(Slot& slot, uint32_t stepIndex, uint64_t execution) {
  const Step& step = steps_[stepIndex];
  recording_.step = stepIndex;
  queueBarriers(step.before);
  commandBuffer_.beginNode([](void* graph) { static_cast<VulkanGraph*>(graph)->beginStep(); }, this, step.rendering);
  // Attachments are accessed by vkCmdBeginRendering itself (load and store operations): a node
  // rendering into them does work even if its job draws nothing.
  if (step.rendering) commandBuffer_.start();

  const graph::Job& job = jobs_[step.node];
  if (job) {
    commandBuffer_.useSet(scopedSets_ ? scopedSets_->set(stepIndex) : VK_NULL_HANDLE);
    VulkanJobContext context(*this, device_, commandBuffer_, execution);
    if (step.rendering) context.setExtent(step.extent);
    job(context);
  }
  const bool started = commandBuffer_.endNode();
  endStep(started);
  queueBarriers(step.after);
  // Releases to other queues and final import states must be recorded before the submit signals.
  if (step.lastOfSubmit && !pendingBarriers_.empty()) flushBarriers();
  slot.started[stepIndex] = started;
  slot.recorded[stepIndex] = 0;  // until endBuffer: the buffer that holds its commands is its block's
}

// The kept buffer of a step is submitted again: move the host state on as recording did (its key
// was the same, so it decided the same), dropping the barriers it holds.
void VulkanGraph::replayStep(const Slot& slot, uint32_t stepIndex) {
  const Step& step = steps_[stepIndex];
  replaying_ = true;
  if (slot.started[stepIndex]) {
    // Its prologue recorded everything queued before it, its own "before" barriers included (and
    // any batch an ownership transfer flushed earlier): nothing of it is left to queue.
    flushBarriers();
    markHeapsTouched(step);
    if (stepIndex == slowStep_) recording_.slot->spinIterations = spin_->iterations();
  } else {
    queueBarriers(step.before);
  }
  queueBarriers(step.after);
  if (step.lastOfSubmit && !pendingBarriers_.empty()) flushBarriers();
  replaying_ = false;
}

VkCommandBuffer VulkanGraph::commandBufferForRecording() {
  if (recording_.cmd != VK_NULL_HANDLE) return recording_.cmd;
  const VkCommandBuffer cmd = recording_.slot->commandBuffers[recording_.bufferStep];
  auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = recording_.usage;
  check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");  // resets what it held
  commandBuffer_.begin(VK_NULL_HANDLE);  // forget descriptor bindings of the previous buffer
  commandBuffer_.begin(cmd);
  recording_.cmd = cmd;
  return cmd;
}

void VulkanGraph::flushBarriers() {
  if (replaying_)
    pendingBarriers_.clear();
  else
    pendingBarriers_.record(commandBufferForRecording());
  pendingSignature_ = 0;
}

void VulkanGraph::beginStep() {
  const Step& step = steps_[recording_.step];
  const VkCommandBuffer cmd = commandBufferForRecording();
  if (device_.debugLabels()) {
    auto label = vkStruct<VkDebugUtilsLabelEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT);
    label.pLabelName = declaration_.nodes()[step.node].name.data();  // NUL-terminated
    std::copy(std::begin(kLabelColors[static_cast<int>(step.type)]), std::end(kLabelColors[static_cast<int>(step.type)]),
              label.color);
    vkCmdBeginDebugUtilsLabelEXT(cmd, &label);
  }
  flushBarriers();
  if (recording_.queries != VK_NULL_HANDLE && timestampMask_[step.logicalQueue] != 0) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, recording_.queries, recording_.step * 2);
  }
  if (step.rendering) {
    vkCmdBeginRendering(cmd, &step.renderingInfo);
    const VkViewport viewport{0, 0, static_cast<float>(step.extent.width), static_cast<float>(step.extent.height), 0, 1};
    const VkRect2D scissor{{0, 0}, {step.extent.width, step.extent.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
  }
}

void VulkanGraph::endStep(bool recorded) {
  if (!recorded) return;  // no label, no timestamps: the node has no GPU time (it reads as 0 ms)
  const Step& step = steps_[recording_.step];
  const VkCommandBuffer cmd = recording_.cmd;
  if (step.rendering) vkCmdEndRendering(cmd);
  if (recording_.step == slowStep_) {
    // debug.slow_pass: the node's own work ends here (third timestamp), then the spin.
    if (recording_.queries != VK_NULL_HANDLE && timestampMask_[step.logicalQueue] != 0) {
      vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, recording_.queries,
                           static_cast<uint32_t>(steps_.size() * 2));
    }
    spin_->record(cmd);
    commandBuffer_.forgetComputeSet();
    recording_.slot->spinIterations = spin_->iterations();
  }
  if (recording_.queries != VK_NULL_HANDLE && timestampMask_[step.logicalQueue] != 0) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, recording_.queries, recording_.step * 2 + 1);
  }
  if (device_.debugLabels()) vkCmdEndDebugUtilsLabelEXT(cmd);
  markHeapsTouched(step);
}

void VulkanGraph::markHeapsTouched(const Step& step) {
  for (uint32_t i = step.firstHeap; i < step.firstHeap + step.heapCount; ++i) heapTouched_[stepHeaps_[i]] = 1;
}

VkCommandBuffer VulkanGraph::stepCommandBuffer(uint32_t step) const {
  if (executions_ == 0) return VK_NULL_HANDLE;
  const Slot& slot = slots_[(executions_ - 1) % slots_.size()];
  return slot.recorded.at(step) ? slot.commandBuffers[step] : VK_NULL_HANDLE;
}

// A same-layout barrier on graph-owned memory that no recorded command has touched yet in this
// execution orders nothing: the memory's previous accesses belong to earlier executions, which
// this one waited for on every queue. Such barriers are skipped; the rest are queued (merged per
// resource) until the next command.
void VulkanGraph::queueBarriers(BarrierList list) {
  for (uint32_t i = list.first; i < list.first + list.count; ++i) {
    const BarrierRef& ref = barrierRefs_[i];
    if (ref.elidable && heapTouched_[ref.heap] == 0) continue;
    const auto add = [&] {
      return ref.image ? pendingBarriers_.add(ref.resource, imageBarriers_[ref.index])
                       : pendingBarriers_.add(ref.resource, bufferBarriers_[ref.index]);
    };
    if (!add()) {
      flushBarriers();
      if (!add()) throw DeviceError("internal: a barrier could not be queued after the batch was recorded");
    }
    pendingSignature_ = mix(pendingSignature_, i + 1);
  }
}

void VulkanGraph::submitAll(const Slot& slot, uint64_t execution, rhi::RunMode mode) {
  const auto& submits = compiled_.submits;
  const uint64_t base = timelineBase(execution);
  std::vector<TimelinePoint>& tail = device_.sequentialTail();

  // Pointers into these vectors are taken below: size them fully first.
  size_t waitCount = 0;
  for (const auto& submit : submits) waitCount += submit.waits.size();
  waitCount += logicalQueues_ * (logicalQueues_ + tail.size());
  waitInfos_.clear();
  waitInfos_.reserve(waitCount);
  signalInfos_.assign(submits.size(), vkStruct<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO));
  commandInfos_.assign(steps_.size(),
                       vkStruct<VkCommandBufferSubmitInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO));
  submitInfos_.clear();

  std::vector<bool> firstOnQueue(logicalQueues_, true);
  const auto addWait = [&](VkSemaphore semaphore, uint64_t value, VkPipelineStageFlags2 stages) {
    auto info = vkStruct<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
    info.semaphore = semaphore;
    info.value = value;
    info.stageMask = stages;
    waitInfos_.push_back(info);
  };
  for (const uint32_t s : submitOrder_) {
    const graph::Submit& submit = submits[s];
    const size_t firstWait = waitInfos_.size();
    for (const auto& wait : submit.waits) {
      addWait(timelines_[wait.queue].get(), base + wait.value, waitStages(wait.stages));
    }
    if (firstOnQueue[submit.queue]) {
      firstOnQueue[submit.queue] = false;
      // Transient memory and imported resources are reused by the next execution: it starts only
      // after the previous one finished on every queue. Sequential runs also wait for the previous
      // sequential run (of any graph).
      if (execution > 0) {
        for (uint32_t q = 0; q < logicalQueues_; ++q) {
          if (compiled_.submitsPerQueue[q] == 0) continue;
          addWait(timelines_[q].get(), timelineBase(execution - 1) + compiled_.submitsPerQueue[q],
                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
        }
      }
      if (mode == rhi::RunMode::Sequential) {
        for (const auto& point : tail) addWait(point.semaphore, point.value, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      }
    }
    VkSemaphoreSubmitInfo& signal = signalInfos_[s];
    signal.semaphore = timelines_[submit.queue].get();
    signal.value = base + submit.signalValue;
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    // The buffers of the submit's steps that hold commands, in step order, from its first step's
    // place in commandInfos_ on.
    uint32_t buffers = 0;
    for (uint32_t step = submit.firstStep; step < submit.firstStep + submit.stepCount; ++step) {
      if (slot.recorded[step]) commandInfos_[submit.firstStep + buffers++].commandBuffer = slot.commandBuffers[step];
    }

    auto info = vkStruct<VkSubmitInfo2>(VK_STRUCTURE_TYPE_SUBMIT_INFO_2);
    info.waitSemaphoreInfoCount = static_cast<uint32_t>(waitInfos_.size() - firstWait);
    info.pWaitSemaphoreInfos = info.waitSemaphoreInfoCount ? &waitInfos_[firstWait] : nullptr;
    info.commandBufferInfoCount = buffers;
    info.pCommandBufferInfos = buffers ? &commandInfos_[submit.firstStep] : nullptr;
    info.signalSemaphoreInfoCount = 1;
    info.pSignalSemaphoreInfos = &signal;
    submitInfos_.push_back(info);
  }

  // One vkQueueSubmit2 per run of consecutive batches for the same device queue.
  size_t first = 0;
  while (first < submitInfos_.size()) {
    const uint32_t queue = deviceQueueOf_[submits[submitOrder_[first]].queue];
    size_t end = first + 1;
    while (end < submitInfos_.size() && deviceQueueOf_[submits[submitOrder_[end]].queue] == queue) ++end;
    check(vkQueueSubmit2(device_.queues()[queue].queue, static_cast<uint32_t>(end - first), &submitInfos_[first],
                         VK_NULL_HANDLE),
          "vkQueueSubmit2 (graph '" + options_.name + "')");
    first = end;
  }

  finishSubmission(execution, mode);
}

// The execution's completion points: what later executions and sequential runs wait for.
void VulkanGraph::finishSubmission(uint64_t execution, rhi::RunMode mode) {
  lastPoints_.clear();
  for (uint32_t q = 0; q < logicalQueues_; ++q) {
    if (compiled_.submitsPerQueue[q] > 0) {
      lastPoints_.push_back({timelines_[q].get(), timelineBase(execution) + compiled_.submitsPerQueue[q]});
    }
  }
  if (mode != rhi::RunMode::Async) device_.sequentialTail() = lastPoints_;
}

bool VulkanGraph::isComplete(uint64_t execution) const {
  if (execution >= executions_) return false;
  const uint64_t base = timelineBase(execution);
  for (uint32_t q = 0; q < logicalQueues_; ++q) {
    if (compiled_.submitsPerQueue[q] == 0) continue;
    uint64_t value = 0;
    check(vkGetSemaphoreCounterValue(device_.device(), timelines_[q].get(), &value), "vkGetSemaphoreCounterValue");
    if (value < base + compiled_.submitsPerQueue[q]) return false;
  }
  return true;
}

void VulkanGraph::waitFor(uint64_t execution) const {
  if (execution >= executions_) return;  // never submitted: nothing to wait for
  std::vector<VkSemaphore> semaphores;
  std::vector<uint64_t> values;
  for (uint32_t q = 0; q < logicalQueues_; ++q) {
    if (compiled_.submitsPerQueue[q] == 0) continue;
    semaphores.push_back(timelines_[q].get());
    values.push_back(timelineBase(execution) + compiled_.submitsPerQueue[q]);
  }
  if (semaphores.empty()) return;
  auto info = vkStruct<VkSemaphoreWaitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_WAIT_INFO);
  info.semaphoreCount = static_cast<uint32_t>(semaphores.size());
  info.pSemaphores = semaphores.data();
  info.pValues = values.data();
  check(vkWaitSemaphores(device_.device(), &info, UINT64_MAX), "vkWaitSemaphores (graph '" + options_.name + "')");
}

void VulkanGraph::waitForAll() const {
  if (executions_ > 0) waitFor(executions_ - 1);
}

// --- VulkanDevice: graph execution entry points ---

std::unique_ptr<rhi::ExecutableGraph> VulkanDevice::compile(graph::FrameGraph&& graph, const rhi::GraphOptions& options) {
  return std::make_unique<VulkanGraph>(*this, std::move(graph), options);
}

rhi::RunTicket VulkanDevice::execute(rhi::ExecutableGraph& graph, rhi::RunMode mode, std::function<void()> onComplete) {
  auto& vulkanGraph = dynamic_cast<VulkanGraph&>(graph);
  invokeFinishedCallbacks();
  const uint64_t execution = vulkanGraph.submit(mode);
  submittedWork_ = true;
  const rhi::RunTicket ticket{vulkanGraph.id(), execution};
  if (onComplete) callbacks_.push_back({ticket, std::move(onComplete)});
  return ticket;
}

bool VulkanDevice::isComplete(const rhi::RunTicket& ticket) const {
  if (ticket.graph >= graphs_.size() || graphs_[ticket.graph] == nullptr) return true;  // graph gone: it waited
  return graphs_[ticket.graph]->isComplete(ticket.execution);
}

void VulkanDevice::wait(const rhi::RunTicket& ticket) {
  if (ticket.graph < graphs_.size() && graphs_[ticket.graph] != nullptr) graphs_[ticket.graph]->waitFor(ticket.execution);
  invokeFinishedCallbacks();
}

void VulkanDevice::poll() { invokeFinishedCallbacks(); }

void VulkanDevice::waitIdle() {
  check(vkDeviceWaitIdle(device_), "vkDeviceWaitIdle");
  invokeFinishedCallbacks();
}

void VulkanDevice::invokeFinishedCallbacks() {
  // Callbacks may be long; take the finished ones out first so they can run more graphs.
  std::vector<std::function<void()>> finished;
  for (auto it = callbacks_.begin(); it != callbacks_.end();) {
    if (isComplete(it->ticket)) {
      finished.push_back(std::move(it->function));
      it = callbacks_.erase(it);
    } else {
      ++it;
    }
  }
  for (auto& callback : finished) callback();
}

uint32_t VulkanDevice::registerGraph(VulkanGraph* graph) {
  graphs_.push_back(graph);
  return static_cast<uint32_t>(graphs_.size() - 1);
}

void VulkanDevice::unregisterGraph(uint32_t id) {
  VulkanGraph* graph = graphs_.at(id);
  graphs_[id] = nullptr;
  if (graph == nullptr) return;
  // The graph waited for its work; its semaphores must not be waited for by later runs.
  auto& tail = sequentialTail_;
  tail.erase(std::remove_if(tail.begin(), tail.end(),
                            [&](const TimelinePoint& p) {
                              return std::any_of(graph->lastPoints().begin(), graph->lastPoints().end(),
                                                 [&](const TimelinePoint& own) { return own.semaphore == p.semaphore; });
                            }),
             tail.end());
}

}  // namespace fgb::vulkan
