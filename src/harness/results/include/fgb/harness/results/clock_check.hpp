// The timer checked against the clock: a run's GPU spans beside the wall time per frame of the
// same frames (submitted back to back, one wait at the end), and the device's clocks and
// temperature at the start and end of measurement where the driver exposes them. A wall time
// more than 3% slower than the span is always given a reason. Plain data and the verdict; the
// probe that samples the device (NVML) lives in the run room.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

struct DeviceSample {
  double smClockMHz = 0.0;
  double memoryClockMHz = 0.0;
  double temperatureC = 0.0;
  double powerW = 0.0;
  uint64_t throttleReasons = 0;  // NVML's clocks-event reasons bit mask (0: none)
};

struct DeviceState {
  std::string source;       // "nvml", or "" when the device could not be sampled
  std::string unavailable;  // why not, when source is ""
  std::optional<DeviceSample> start, end;
  // The SM clock moved between start and end by more than kClockChangeShare (and 15 MHz).
  [[nodiscard]] bool clocksChanged() const;
};
inline constexpr double kClockChangeShare = 0.02;

// A wall time per frame this much slower than the span needs a reason.
inline constexpr double kWallSlowerThanSpan = 0.03;

struct WallClock {
  uint32_t frames = 0;
  double wallMsPerFrame = 0.0;  // measured frames' wall time / frames (frames in flight overlap)
  double spanMs = 0.0;          // median span of a frame: its first to its last timestamp
  double meanSpanMs = 0.0;      // the wall time adds up means: slow frames lift it above the median
  // Mean GPU time between one frame's last timestamp and the next frame's first: idle when
  // positive, frames overlapping when negative. Absent without absolute frame starts.
  std::optional<double> betweenFramesMs;
  double hostMsPerFrame = 0.0;  // median host time the frame costs (recording and submitting)
  std::string reason;           // why the wall time is more than 3% slower than the span; "" if not
  [[nodiscard]] double slowerThanSpan() const { return spanMs > 0.0 ? wallMsPerFrame / spanMs - 1.0 : 0.0; }
};

struct FrameClock {
  double spanMs = 0.0;
  double startMs = -1.0;  // on the device's timestamp clock; < 0 unknown
  double hostMs = 0.0;
};

// The measured frames' spans and, where the wall time per frame is more than 3% slower than the
// median span, the reason: a clock change (from `state`), CPU-bound (the host needs most of a
// frame's wall time), else the larger part of the excess: submit bubbles (the GPU idles between
// frames) or uneven frames (slow frames lift the mean span above the median).
WallClock checkWallClock(const std::vector<FrameClock>& frames, double wallMs, const DeviceState& state);

// Two rounds of measurement of one configuration as one (until-stable runs measure in rounds):
// wall time and time between frames weighted by frames; spans and host times over all frames;
// the device state from the first round's start to the last round's end; the reason again.
void appendWallClock(WallClock& total, DeviceState& totalState, const WallClock& round, const DeviceState& roundState,
                     const std::vector<double>& allSpansMs, const std::vector<double>& allHostMs);

nlohmann::json toJson(const WallClock& clock);
nlohmann::json toJson(const DeviceState& state);
// The terminal's and report's lines: "span 0.930 ms, wall 0.874 ms per frame (frames overlap)".
std::string describeWallClock(const WallClock& clock);
std::string describeDeviceState(const DeviceState& state);

}  // namespace fgb::harness
