#include "barrier_batch.hpp"

namespace fgb::vulkan {
namespace {

template <class Barrier>
bool transfersOwnership(const Barrier& barrier) {
  return barrier.srcQueueFamilyIndex != barrier.dstQueueFamilyIndex;
}

// `later` follows `earlier` with no command in between: one barrier does both. Its source scope
// is the earlier one's (the later one's sources recorded nothing since); the destination scopes
// add up, since the work that needed either one follows.
void merge(VkImageMemoryBarrier2& earlier, const VkImageMemoryBarrier2& later) {
  earlier.dstStageMask |= later.dstStageMask;
  earlier.dstAccessMask |= later.dstAccessMask;
  earlier.newLayout = later.newLayout;
}

void merge(VkBufferMemoryBarrier2& earlier, const VkBufferMemoryBarrier2& later) {
  earlier.dstStageMask |= later.dstStageMask;
  earlier.dstAccessMask |= later.dstAccessMask;
}

}  // namespace

template <class Barrier>
bool BarrierBatch::addTo(std::vector<Barrier>& list, uint32_t resource, const Barrier& barrier) {
  uint32_t& slot = slotOf_[resource];
  if (slot != kNone) {
    if (transfersOwnership(list[slot]) || transfersOwnership(barrier)) return false;
    merge(list[slot], barrier);
    return true;
  }
  slot = static_cast<uint32_t>(list.size());
  list.push_back(barrier);
  resources_.push_back(resource);
  return true;
}

bool BarrierBatch::add(uint32_t resource, const VkImageMemoryBarrier2& barrier) {
  return addTo(images_, resource, barrier);
}

bool BarrierBatch::add(uint32_t resource, const VkBufferMemoryBarrier2& barrier) {
  return addTo(buffers_, resource, barrier);
}

void BarrierBatch::record(VkCommandBuffer cmd) {
  if (empty()) return;
  auto info = vkStruct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
  info.imageMemoryBarrierCount = static_cast<uint32_t>(images_.size());
  info.pImageMemoryBarriers = images_.data();
  info.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers_.size());
  info.pBufferMemoryBarriers = buffers_.data();
  vkCmdPipelineBarrier2(cmd, &info);
  clear();
}

void BarrierBatch::clear() {
  images_.clear();
  buffers_.clear();
  for (const uint32_t resource : resources_) slotOf_[resource] = kNone;
  resources_.clear();
}

}  // namespace fgb::vulkan
