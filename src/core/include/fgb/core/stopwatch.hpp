// Host wall-clock intervals in milliseconds, for the phases the harness reports apart from GPU
// time (start-up, pipeline creation, readback, encoding).
#pragma once

#include <chrono>

namespace fgb {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  // Milliseconds since construction or the previous lap; starts the next interval.
  double lap() {
    const Clock::time_point now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return ms;
  }
  [[nodiscard]] double elapsedMs() const {
    return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

 private:
  Clock::time_point start_ = Clock::now();
};

}  // namespace fgb
