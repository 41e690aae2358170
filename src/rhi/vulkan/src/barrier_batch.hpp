// Barriers waiting to be recorded. The executor queues each node's barriers here instead of
// recording them at once; the batch is recorded as one vkCmdPipelineBarrier2 right before the next
// command that may depend on it (the first command of a node that records work) or at the end of
// the command buffer. Barriers queued on the same resource merge into one: the first one's source
// scope and old layout, the union of destination scopes, the last one's new layout. So a node
// that records nothing costs no barrier command, and a node's "after" barriers share one call with
// the next node's "before" barriers.
#pragma once

#include "vk.hpp"

#include <cstdint>
#include <vector>

namespace fgb::vulkan {

class BarrierBatch {
 public:
  void resize(size_t resourceCount) { slotOf_.assign(resourceCount, kNone); }

  // Queues `barrier`, merged with one queued on the same resource. False (nothing queued) when
  // that cannot be: either half of an ownership transfer absorbs nothing. Record, then add again.
  [[nodiscard]] bool add(uint32_t resource, const VkImageMemoryBarrier2& barrier);
  [[nodiscard]] bool add(uint32_t resource, const VkBufferMemoryBarrier2& barrier);
  [[nodiscard]] bool empty() const { return images_.empty() && buffers_.empty(); }
  [[nodiscard]] const std::vector<VkImageMemoryBarrier2>& images() const { return images_; }
  [[nodiscard]] const std::vector<VkBufferMemoryBarrier2>& buffers() const { return buffers_; }
  // Records every queued barrier into `cmd` (one call) and empties the batch.
  void record(VkCommandBuffer cmd);
  // Empties the batch without recording: a kept command buffer recorded these barriers already.
  void clear();

 private:
  static constexpr uint32_t kNone = ~0u;
  template <class Barrier>
  bool addTo(std::vector<Barrier>& list, uint32_t resource, const Barrier& barrier);

  std::vector<VkImageMemoryBarrier2> images_;
  std::vector<VkBufferMemoryBarrier2> buffers_;
  std::vector<uint32_t> slotOf_;     // per resource: its queued barrier in images_ or buffers_
  std::vector<uint32_t> resources_;  // resources with a queued barrier
};

}  // namespace fgb::vulkan
