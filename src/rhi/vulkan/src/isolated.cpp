// RunMode::Isolated, the pass-cost calibration: the graph's recorded steps run one at a time on an
// otherwise idle device. The device is drained first; then each step's command buffer is submitted
// alone on its queue and waited for before the next, in the plan's submit order (which respects
// every dependency, so barriers and queue-ownership transfers recorded in the buffers stay valid).
// Each submit's timeline value is still signalled, by an empty batch after its steps, so later
// executions chain onto this one as onto any other.
#include "executable_graph.hpp"

namespace fgb::vulkan {

void VulkanGraph::submitIsolated(const Slot& slot, uint64_t execution) {
  check(vkDeviceWaitIdle(device_.device()), "vkDeviceWaitIdle (isolated run of graph '" + options_.name + "')");
  const uint64_t base = timelineBase(execution);
  for (const uint32_t s : submitOrder_) {
    const graph::Submit& submit = compiled_.submits[s];
    const VkQueue queue = device_.queues()[deviceQueueOf_[submit.queue]].queue;
    for (uint32_t step = submit.firstStep; step < submit.firstStep + submit.stepCount; ++step) {
      if (!slot.recorded[step]) continue;
      auto command = vkStruct<VkCommandBufferSubmitInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO);
      command.commandBuffer = slot.commandBuffers[step];
      auto info = vkStruct<VkSubmitInfo2>(VK_STRUCTURE_TYPE_SUBMIT_INFO_2);
      info.commandBufferInfoCount = 1;
      info.pCommandBufferInfos = &command;
      check(vkQueueSubmit2(queue, 1, &info, VK_NULL_HANDLE), "vkQueueSubmit2 (isolated step)");
      check(vkQueueWaitIdle(queue), "vkQueueWaitIdle (isolated step)");
    }
    auto signal = vkStruct<VkSemaphoreSubmitInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO);
    signal.semaphore = timelines_[submit.queue].get();
    signal.value = base + submit.signalValue;
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    auto info = vkStruct<VkSubmitInfo2>(VK_STRUCTURE_TYPE_SUBMIT_INFO_2);
    info.signalSemaphoreInfoCount = 1;
    info.pSignalSemaphoreInfos = &signal;
    check(vkQueueSubmit2(queue, 1, &info, VK_NULL_HANDLE), "vkQueueSubmit2 (isolated submit's signal)");
  }
  finishSubmission(execution, rhi::RunMode::Isolated);
}

}  // namespace fgb::vulkan
