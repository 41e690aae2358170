// MSAA is clamped to what the device supports: the highest supported sample count not above the
// request. Supported sets need not be contiguous (lavapipe: {1, 4}), so "min(request, max)" is
// wrong: 2 samples on lavapipe must give 1, not 2.
#include <fgb/rhi/device.hpp>

#include <gtest/gtest.h>

namespace fgb::test {
namespace {

constexpr uint32_t kLavapipe = 1u | 4u;
constexpr uint32_t kAll = 1u | 2u | 4u | 8u;

TEST(SampleCounts, ClampsToTheHighestSupportedCountNotAboveTheRequest) {
  EXPECT_EQ(rhi::clampSampleCount(1, kLavapipe), 1u);
  EXPECT_EQ(rhi::clampSampleCount(2, kLavapipe), 1u);
  EXPECT_EQ(rhi::clampSampleCount(4, kLavapipe), 4u);
  EXPECT_EQ(rhi::clampSampleCount(8, kLavapipe), 4u);
  for (uint32_t samples : {1u, 2u, 4u, 8u}) EXPECT_EQ(rhi::clampSampleCount(samples, kAll), samples);
  EXPECT_EQ(rhi::clampSampleCount(8, 1u), 1u);
  EXPECT_EQ(rhi::clampSampleCount(8, 1u | 2u), 2u);
  EXPECT_EQ(rhi::clampSampleCount(0, kAll), 1u);  // nothing below: single-sampled
}

}  // namespace
}  // namespace fgb::test
