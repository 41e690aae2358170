#include <fgb/rhi/range_allocator.hpp>

#include <gtest/gtest.h>

#include <stdexcept>

using fgb::rhi::RangeAllocator;

TEST(RangeAllocator, AllocatesAlignedNonOverlappingRanges) {
  RangeAllocator ranges(1024);
  const auto a = ranges.allocate(100, 1);
  const auto b = ranges.allocate(100, 256);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(*a, 0u);
  EXPECT_EQ(*b, 256u);  // aligned up past a's end
  EXPECT_EQ(ranges.used(), 200u);
  EXPECT_EQ(ranges.freeRanges(), 2u);  // the padding [100, 256) and the tail
}

TEST(RangeAllocator, RejectsWhatDoesNotFitAndBadAlignment) {
  RangeAllocator ranges(512);
  EXPECT_FALSE(ranges.allocate(513, 1));
  EXPECT_FALSE(ranges.allocate(16, 3));
  EXPECT_FALSE(ranges.allocate(0, 1));
  ASSERT_TRUE(ranges.allocate(512, 512));
  EXPECT_FALSE(ranges.allocate(1, 1));
}

TEST(RangeAllocator, FreeCoalescesNeighboursSoTheWholeBlockIsReusable) {
  RangeAllocator ranges(300);
  const auto a = ranges.allocate(100, 1);
  const auto b = ranges.allocate(100, 1);
  const auto c = ranges.allocate(100, 1);
  ASSERT_TRUE(a && b && c);
  ranges.free(*a);
  ranges.free(*c);
  EXPECT_EQ(ranges.freeRanges(), 2u);
  ranges.free(*b);
  EXPECT_EQ(ranges.freeRanges(), 1u);
  EXPECT_TRUE(ranges.empty());
  const auto whole = ranges.allocate(300, 1);
  ASSERT_TRUE(whole);
  EXPECT_EQ(*whole, 0u);
}

TEST(RangeAllocator, DoubleFreeThrows) {
  RangeAllocator ranges(64);
  const auto a = ranges.allocate(8, 8);
  ASSERT_TRUE(a);
  ranges.free(*a);
  EXPECT_THROW(ranges.free(*a), std::logic_error);
  EXPECT_THROW(ranges.free(32), std::logic_error);
}
