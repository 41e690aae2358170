// Per-node GPU timestamps. Each step writes a pair of timestamps; results of an execution are read
// once it is known complete (its timeline values reached), so reading never waits for the GPU:
// during execution N the results of N-1 are normally ready. timestampValidBits masks the raw
// values (wrap-around safe differences) and timestampPeriod converts ticks to nanoseconds.
#include "executable_graph.hpp"

#include <algorithm>
#include <limits>

namespace fgb::vulkan {

void VulkanGraph::collectTimings(Slot& slot) {
  if (!slot.timed) return;
  slot.timed = false;
  const uint32_t queryCount = queryCount_;
  std::vector<uint64_t> results(static_cast<size_t>(queryCount) * 2);  // value, availability
  const VkResult result = vkGetQueryPoolResults(device_.device(), slot.queries.get(), 0, queryCount,
                                                results.size() * sizeof(uint64_t), results.data(), 2 * sizeof(uint64_t),
                                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
  if (result != VK_SUCCESS && result != VK_NOT_READY) check(result, "vkGetQueryPoolResults");

  const double periodMs = device_.adapter().timestampPeriodNs * 1e-6;
  rhi::GraphTimings timings;
  timings.execution = slot.execution;
  timings.nodeMs.assign(declaration_.nodes().size(), 0.0);
  timings.nodeStartMs.assign(declaration_.nodes().size(), -1.0);
  const auto available = [&](uint32_t s) {
    const uint64_t* pair = &results[static_cast<size_t>(s) * 4];
    return timestampMask_[steps_[s].logicalQueue] != 0 && pair[1] != 0 && pair[3] != 0;
  };
  // Steps are grouped by queue, not by time: the frame starts at the earliest begin timestamp.
  // Differences are taken in masked (wrapping) arithmetic, so a counter wrap costs nothing.
  bool haveReference = false;
  uint64_t reference = 0;
  for (uint32_t s = 0; s < steps_.size(); ++s) {
    if (!available(s)) continue;
    const uint64_t begin = results[static_cast<size_t>(s) * 4];
    const uint64_t mask = timestampMask_[steps_[s].logicalQueue];
    const uint64_t ahead = (reference - begin) & mask;
    if (!haveReference || (ahead != 0 && ahead < (mask >> 1))) reference = begin;
    haveReference = true;
  }
  uint64_t latestEnd = 0;
  for (uint32_t s = 0; s < steps_.size(); ++s) {
    if (!available(s)) continue;
    const uint64_t mask = timestampMask_[steps_[s].logicalQueue];
    const uint64_t begin = results[static_cast<size_t>(s) * 4];
    const uint64_t end = results[static_cast<size_t>(s) * 4 + 2];
    const uint32_t node = steps_[s].node;
    timings.nodeMs[node] = static_cast<double>((end - begin) & mask) * periodMs;
    timings.nodeStartMs[node] = static_cast<double>((begin - reference) & mask) * periodMs;
    latestEnd = std::max(latestEnd, (end - reference) & mask);
  }
  timings.gpuMs = static_cast<double>(latestEnd) * periodMs;
  if (haveReference) timings.startMs = static_cast<double>(reference) * periodMs;
  if (spin_ && available(slowStep_) && results[static_cast<size_t>(steps_.size()) * 4 + 1] != 0) {
    // debug.slow_pass: begin .. own end .. end (after the spin).
    const uint64_t mask = timestampMask_[steps_[slowStep_].logicalQueue];
    const uint64_t begin = results[static_cast<size_t>(slowStep_) * 4];
    const uint64_t own = results[static_cast<size_t>(steps_.size()) * 4];
    const uint64_t end = results[static_cast<size_t>(slowStep_) * 4 + 2];
    spin_->observe(slot.execution, static_cast<double>((own - begin) & mask) * periodMs,
                   static_cast<double>((end - own) & mask) * periodMs, slot.spinIterations);
  }
  timings_.push_back(std::move(timings));
}

void VulkanGraph::collectFinishedTimings() {
  // Oldest first, so timings come out in execution order.
  std::vector<Slot*> finished;
  for (auto& slot : slots_) {
    if (slot.pending && isComplete(slot.execution)) finished.push_back(&slot);
  }
  std::sort(finished.begin(), finished.end(), [](const Slot* a, const Slot* b) { return a->execution < b->execution; });
  for (Slot* slot : finished) {
    slot->pending = false;
    collectTimings(*slot);
  }
}

std::vector<rhi::GraphTimings> VulkanGraph::takeTimings() {
  collectFinishedTimings();
  std::vector<rhi::GraphTimings> taken(std::make_move_iterator(timings_.begin()), std::make_move_iterator(timings_.end()));
  timings_.clear();
  return taken;
}

}  // namespace fgb::vulkan
