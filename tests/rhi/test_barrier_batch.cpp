// BarrierBatch merges barriers queued on one resource with no command between them: the first
// source scope and old layout, the union of destination scopes, the last new layout. Ownership
// transfer halves merge with nothing.
#include "barrier_batch.hpp"

#include <gtest/gtest.h>

namespace fgb::vulkan {
namespace {

VkImageMemoryBarrier2 image(VkPipelineStageFlags2 src, VkPipelineStageFlags2 dst, VkImageLayout from, VkImageLayout to) {
  auto b = vkStruct<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
  b.srcStageMask = src;
  b.srcAccessMask = VK_ACCESS_2_SHADER_WRITE_BIT;
  b.dstStageMask = dst;
  b.dstAccessMask = VK_ACCESS_2_SHADER_READ_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  return b;
}

VkBufferMemoryBarrier2 buffer(VkPipelineStageFlags2 src, VkPipelineStageFlags2 dst) {
  auto b = vkStruct<VkBufferMemoryBarrier2>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2);
  b.srcStageMask = src;
  b.dstStageMask = dst;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  return b;
}

TEST(BarrierBatch, BarriersOnOneResourceMergeIntoOne) {
  BarrierBatch batch;
  batch.resize(4);
  EXPECT_TRUE(batch.empty());
  ASSERT_TRUE(batch.add(2, image(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                                 VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL)));
  ASSERT_TRUE(batch.add(2, image(VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)));
  ASSERT_TRUE(batch.add(3, image(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_GENERAL)));
  ASSERT_EQ(batch.images().size(), 2u);
  const VkImageMemoryBarrier2& merged = batch.images()[0];
  EXPECT_EQ(merged.srcStageMask, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(merged.dstStageMask, VK_PIPELINE_STAGE_2_TRANSFER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(merged.oldLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(merged.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_FALSE(batch.empty());
}

TEST(BarrierBatch, BufferBarriersMergeDestinationScopes) {
  BarrierBatch batch;
  batch.resize(1);
  ASSERT_TRUE(batch.add(0, buffer(VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT)));
  ASSERT_TRUE(batch.add(0, buffer(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT)));
  ASSERT_EQ(batch.buffers().size(), 1u);
  EXPECT_EQ(batch.buffers()[0].srcStageMask, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
  EXPECT_EQ(batch.buffers()[0].dstStageMask, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT);
}

TEST(BarrierBatch, OwnershipTransfersDoNotMerge) {
  BarrierBatch batch;
  batch.resize(1);
  VkBufferMemoryBarrier2 acquire = buffer(VK_PIPELINE_STAGE_2_NONE, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  acquire.srcQueueFamilyIndex = 1;
  acquire.dstQueueFamilyIndex = 0;
  ASSERT_TRUE(batch.add(0, acquire));
  EXPECT_FALSE(batch.add(0, buffer(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT)));
  EXPECT_EQ(batch.buffers().size(), 1u);
  EXPECT_EQ(batch.buffers()[0].dstStageMask, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

}  // namespace
}  // namespace fgb::vulkan
