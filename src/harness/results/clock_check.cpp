#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fgb/harness/results/clock_check.hpp>
#include <fgb/harness/stats/stats.hpp>

namespace fgb::harness {
namespace {

// Share of the wall time per frame that the host's own work must take to call a run CPU-bound.
constexpr double kCpuBoundShare = 0.8;

double medianOf(const std::vector<double>& values) {
  return summarize(values).median;
}

double meanOf(const std::vector<double>& values) {
  return summarize(values).mean;
}

std::optional<double> meanBetweenFrames(const std::vector<FrameClock>& frames) {
  std::vector<double> gaps;
  for (size_t i = 1; i < frames.size(); ++i) {
    if (frames[i - 1].startMs < 0.0 || frames[i].startMs < 0.0) continue;
    gaps.push_back(frames[i].startMs - (frames[i - 1].startMs + frames[i - 1].spanMs));
  }
  if (gaps.empty()) return std::nullopt;
  return meanOf(gaps);
}

std::string reasonFor(const WallClock& clock, const DeviceState& state) {
  if (state.clocksChanged()) {
    return fmt::format("clock change: the SM clock went from {:.0f} to {:.0f} MHz during measurement",
                       state.start->smClockMHz, state.end->smClockMHz);
  }
  if (clock.hostMsPerFrame >= kCpuBoundShare * clock.wallMsPerFrame) {
    return fmt::format("CPU-bound: the host needs {:.3f} ms per frame to record and submit it", clock.hostMsPerFrame);
  }
  // wall per frame = mean span + mean time between frames; the excess over the median span splits
  // into the slow frames' share (mean - median span) and the idle share.
  const double uneven = clock.meanSpanMs - clock.spanMs;
  const double idle = clock.betweenFramesMs ? *clock.betweenFramesMs : clock.wallMsPerFrame - clock.meanSpanMs;
  const std::string bubbles = fmt::format(
      "submit bubbles: the GPU idles {:.3f} ms between frames on average (the "
      "host records a frame in {:.3f} ms)",
      std::max(0.0, idle), clock.hostMsPerFrame);
  const std::string slowFrames =
      fmt::format("uneven frames: slow frames lift the mean span {:.3f} ms above the median", uneven);
  // The smaller share is named only where it is a share at all (above half a microsecond).
  constexpr double kNegligibleMs = 0.0005;
  if (idle >= uneven) return uneven > kNegligibleMs ? bubbles + "; " + slowFrames : bubbles;
  return idle > kNegligibleMs ? slowFrames + "; " + bubbles : slowFrames;
}

}  // namespace

bool DeviceState::clocksChanged() const {
  if (!start || !end || start->smClockMHz <= 0.0) return false;
  const double change = std::abs(end->smClockMHz - start->smClockMHz);
  return change > 15.0 && change > kClockChangeShare * start->smClockMHz;
}

WallClock checkWallClock(const std::vector<FrameClock>& frames, double wallMs, const DeviceState& state) {
  WallClock clock;
  clock.frames = static_cast<uint32_t>(frames.size());
  if (frames.empty()) return clock;
  std::vector<double> spans, host;
  for (const auto& frame : frames) {
    spans.push_back(frame.spanMs);
    host.push_back(frame.hostMs);
  }
  clock.wallMsPerFrame = wallMs / static_cast<double>(frames.size());
  clock.spanMs = medianOf(spans);
  clock.meanSpanMs = meanOf(spans);
  clock.hostMsPerFrame = medianOf(host);
  clock.betweenFramesMs = meanBetweenFrames(frames);
  if (clock.slowerThanSpan() > kWallSlowerThanSpan) clock.reason = reasonFor(clock, state);
  return clock;
}

void appendWallClock(WallClock& total, DeviceState& totalState, const WallClock& round, const DeviceState& roundState,
                     const std::vector<double>& allSpansMs, const std::vector<double>& allHostMs) {
  if (round.frames == 0) return;
  if (total.frames == 0) {
    total = round;
    totalState = roundState;
    return;
  }
  const double before = total.frames, added = round.frames, frames = before + added;
  total.wallMsPerFrame = (total.wallMsPerFrame * before + round.wallMsPerFrame * added) / frames;
  if (total.betweenFramesMs && round.betweenFramesMs) {
    total.betweenFramesMs = (*total.betweenFramesMs * before + *round.betweenFramesMs * added) / frames;
  }
  total.frames += round.frames;
  total.spanMs = medianOf(allSpansMs);
  total.meanSpanMs = meanOf(allSpansMs);
  total.hostMsPerFrame = medianOf(allHostMs);
  if (!totalState.start) totalState = roundState;
  totalState.end = roundState.end;
  total.reason = total.slowerThanSpan() > kWallSlowerThanSpan ? reasonFor(total, totalState) : "";
}

nlohmann::json toJson(const WallClock& clock) {
  nlohmann::json json{{"frames", clock.frames},
                      {"wall_ms_per_frame", clock.wallMsPerFrame},
                      {"span_ms", clock.spanMs},
                      {"mean_span_ms", clock.meanSpanMs},
                      {"host_ms_per_frame", clock.hostMsPerFrame},
                      {"wall_slower_than_span", clock.slowerThanSpan()}};
  json["between_frames_ms"] = clock.betweenFramesMs ? nlohmann::json(*clock.betweenFramesMs) : nlohmann::json();
  if (!clock.reason.empty()) json["reason"] = clock.reason;
  return json;
}

nlohmann::json toJson(const DeviceState& state) {
  const auto sample = [](const std::optional<DeviceSample>& s) -> nlohmann::json {
    if (!s) return nullptr;
    return {{"sm_clock_mhz", s->smClockMHz},
            {"memory_clock_mhz", s->memoryClockMHz},
            {"temperature_c", s->temperatureC},
            {"power_w", s->powerW},
            {"throttle_reasons", s->throttleReasons}};
  };
  if (state.source.empty()) return {{"source", nullptr}, {"unavailable", state.unavailable}};
  return {{"source", state.source},
          {"start", sample(state.start)},
          {"end", sample(state.end)},
          {"clocks_changed", state.clocksChanged()}};
}

std::string describeWallClock(const WallClock& clock) {
  if (clock.frames == 0) return "";
  std::string line = fmt::format(
      "span {:.3f} ms (median, first to last timestamp), wall {:.3f} ms per frame ({} frames "
      "back to back, one wait at the end)",
      clock.spanMs, clock.wallMsPerFrame, clock.frames);
  if (!clock.reason.empty())
    return line + fmt::format(": wall {:+.1f}%: {}", 100.0 * clock.slowerThanSpan(), clock.reason);
  if (clock.slowerThanSpan() < -kWallSlowerThanSpan) return line + ": frames in flight overlap on the GPU";
  return line;
}

std::string describeDeviceState(const DeviceState& state) {
  if (state.source.empty()) return "device state: not sampled (" + state.unavailable + ")";
  if (!state.start || !state.end) return "device state: " + state.source + " gave no sample";
  std::string line = fmt::format(
      "device state ({}): SM {:.0f} → {:.0f} MHz, memory {:.0f} → {:.0f} MHz, {:.0f} → {:.0f} °C, "
      "{:.0f} → {:.0f} W",
      state.source, state.start->smClockMHz, state.end->smClockMHz, state.start->memoryClockMHz,
      state.end->memoryClockMHz, state.start->temperatureC, state.end->temperatureC, state.start->powerW,
      state.end->powerW);
  if (state.clocksChanged()) line += " — warning: the clocks changed during measurement";
  return line;
}

}  // namespace fgb::harness
