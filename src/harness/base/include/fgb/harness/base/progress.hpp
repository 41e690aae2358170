// A one-line progress bar (with an ETA from the rate so far) on stderr for long runs; silent under --quiet or when stderr is not a TTY.
#pragma once

#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>

namespace fgb::harness {

class ProgressBar {
 public:
  // enabled: draw at all (callers pass !quiet && stderrIsTerminal()).
  ProgressBar(std::ostream& out, std::string label, bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void update(uint32_t done, uint32_t total);
  void finish();  // clears the line

  static bool stderrIsTerminal();

 private:
  std::ostream& out_;
  std::string label_;
  bool enabled_;
  std::string etaText(uint32_t done, uint32_t total, std::chrono::steady_clock::time_point now) const;

  bool drawn_ = false;
  bool started_ = false;
  std::chrono::steady_clock::time_point start_{}, lastDraw_{};
};

}  // namespace fgb::harness
