// The timer against the clock: the wall time per frame beside the spans, the reason given when it
// is more than 3% slower, and the device probe (a fake NVML loaded through dlopen).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fgb/harness/results/clock_check.hpp>
#include <fgb/harness/run/device_probe.hpp>

namespace fgb::harness {
namespace {

std::vector<FrameClock> frames(int count, double span, double between, double host) {
  std::vector<FrameClock> result;
  for (int i = 0; i < count; ++i) result.push_back({span, 100.0 + i * (span + between), host});
  return result;
}

TEST(WallClock, AgreesWithSpanNeedsNoReason) {
  const WallClock clock = checkWallClock(frames(10, 1.0, 0.01, 0.05), 10.1, {});
  EXPECT_NEAR(clock.wallMsPerFrame, 1.01, 1e-12);
  EXPECT_NEAR(clock.spanMs, 1.0, 1e-12);
  ASSERT_TRUE(clock.betweenFramesMs);
  EXPECT_NEAR(*clock.betweenFramesMs, 0.01, 1e-9);
  EXPECT_TRUE(clock.reason.empty());
}

TEST(WallClock, OverlappingFramesAreFasterThanTheirSpan) {
  const WallClock clock = checkWallClock(frames(10, 0.93, -0.056, 0.04), 8.74, {});
  EXPECT_LT(clock.slowerThanSpan(), -0.03);
  EXPECT_TRUE(clock.reason.empty());
  EXPECT_NE(describeWallClock(clock).find("overlap"), std::string::npos);
}

TEST(WallClock, IdleGpuBetweenFramesIsSubmitBubbles) {
  const WallClock clock = checkWallClock(frames(10, 1.0, 0.2, 0.05), 12.0, {});
  EXPECT_EQ(clock.reason.rfind("submit bubbles", 0), 0u) << clock.reason;
  EXPECT_NE(clock.reason.find("0.200"), std::string::npos) << clock.reason;
}

TEST(WallClock, SlowFramesAreUnevenFrames) {
  std::vector<FrameClock> clocks = frames(10, 1.0, 0.0, 0.05);
  for (int i = 0; i < 10; ++i) clocks[i].startMs = 100.0 + i * 1.0 + (i > 7 ? 1.0 * (i - 7) : 0.0);
  clocks[8].spanMs = clocks[9].spanMs = 2.0;  // two slow frames: median 1.0, mean 1.2
  const WallClock clock = checkWallClock(clocks, 12.0, {});
  EXPECT_NEAR(clock.meanSpanMs, 1.2, 1e-12);
  EXPECT_EQ(clock.reason.rfind("uneven frames", 0), 0u) << clock.reason;
}

TEST(WallClock, HostTakingTheFrameIsCpuBound) {
  const WallClock clock = checkWallClock(frames(10, 1.0, 0.5, 1.4), 15.0, {});
  EXPECT_NE(clock.reason.find("CPU-bound"), std::string::npos) << clock.reason;
}

TEST(WallClock, ClockChangeComesFirst) {
  DeviceState state;
  state.source = "nvml";
  state.start = DeviceSample{1980, 2619, 40, 300, 0};
  state.end = DeviceSample{1500, 2619, 80, 300, 0};
  EXPECT_TRUE(state.clocksChanged());
  const WallClock clock = checkWallClock(frames(10, 1.0, 0.5, 1.4), 15.0, state);
  EXPECT_NE(clock.reason.find("clock change"), std::string::npos) << clock.reason;
  EXPECT_NE(describeDeviceState(state).find("warning"), std::string::npos);
  state.end->smClockMHz = 1975;  // within the noise of the clock's reading
  EXPECT_FALSE(state.clocksChanged());
}

TEST(WallClock, RoundsAddUpWeightedByFrames) {
  const auto first = frames(10, 1.0, 0.0, 0.05);
  const auto second = frames(30, 2.0, 0.0, 0.05);
  WallClock total = checkWallClock(first, 10.0, {});
  DeviceState state;
  std::vector<double> spans(10, 1.0), host(40, 0.05);
  spans.resize(40, 2.0);
  appendWallClock(total, state, checkWallClock(second, 60.0, {}), {}, spans, host);
  EXPECT_EQ(total.frames, 40u);
  EXPECT_NEAR(total.wallMsPerFrame, 70.0 / 40.0, 1e-12);
  EXPECT_NEAR(total.spanMs, 2.0, 1e-12);
  EXPECT_NEAR(total.meanSpanMs, 1.75, 1e-12);
  EXPECT_TRUE(total.reason.empty()) << total.reason;
}

TEST(DeviceProbe, WithoutTheLibrarySaysWhy) {
  setenv("FGBENCH_NVML_LIBRARY", "/nonexistent/libnvidia-ml.so.1", 1);
  const DeviceProbe probe(render::DeviceDescription{});
  unsetenv("FGBENCH_NVML_LIBRARY");
  EXPECT_FALSE(probe.available());
  EXPECT_FALSE(probe.sample());
  EXPECT_NE(probe.unavailable().find("libnvidia-ml"), std::string::npos) << probe.unavailable();
}

TEST(DeviceProbe, SamplesTheDeviceWithTheVulkanUuid) {
  setenv("FGBENCH_NVML_LIBRARY", FGBENCH_FAKE_NVML, 1);
  render::DeviceDescription device;
  device.uuid = "00112233445566778899aabbccddeeff";
  {
    const DeviceProbe probe(device);
    ASSERT_TRUE(probe.available()) << probe.unavailable();
    void* fake = dlopen(FGBENCH_FAKE_NVML, RTLD_NOW | RTLD_NOLOAD);
    ASSERT_NE(fake, nullptr);
    const auto setSmClock = reinterpret_cast<void (*)(unsigned)>(dlsym(fake, "fakeNvmlSetSmClock"));
    setSmClock(1980);
    const auto start = probe.sample();
    setSmClock(1410);
    const auto end = probe.sample();
    ASSERT_TRUE(start && end);
    EXPECT_EQ(start->smClockMHz, 1980);
    EXPECT_EQ(end->smClockMHz, 1410);
    EXPECT_EQ(start->memoryClockMHz, 2619);
    EXPECT_NEAR(start->powerW, 123.456, 1e-9);
    const DeviceState state{"nvml", "", start, end};
    EXPECT_TRUE(state.clocksChanged());
    dlclose(fake);
  }
  device.uuid = "ffffffffffffffffffffffffffffffff";
  const DeviceProbe other(device);
  unsetenv("FGBENCH_NVML_LIBRARY");
  EXPECT_FALSE(other.available());
  EXPECT_NE(other.unavailable().find("UUID"), std::string::npos) << other.unavailable();
}

}  // namespace
}  // namespace fgb::harness
