#include <fgb/harness/base/progress.hpp>

#include <unistd.h>

#include <cstdio>

namespace fgb::harness {
namespace {
constexpr int kBarWidth = 30;
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);  // keeps terminal output cheap
}  // namespace

ProgressBar::ProgressBar(std::ostream& out, std::string label, bool enabled)
    : out_(out), label_(std::move(label)), enabled_(enabled) {}

ProgressBar::~ProgressBar() { finish(); }

bool ProgressBar::stderrIsTerminal() { return isatty(fileno(stderr)) != 0; }

void ProgressBar::update(uint32_t done, uint32_t total) {
  if (!enabled_ || total == 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && done < total && now - lastDraw_ < kRedrawInterval) return;
  lastDraw_ = now;
  if (!started_) {
    started_ = true;
    start_ = now;
  }
  const int filled = static_cast<int>(static_cast<uint64_t>(done) * kBarWidth / total);
  out_ << '\r' << label_ << " [" << std::string(static_cast<std::size_t>(filled), '#')
       << std::string(static_cast<std::size_t>(kBarWidth - filled), '.') << "] " << done << '/' << total << etaText(done, total, now) << std::flush;
  drawn_ = true;
}

// " ETA 1m05s" from the rate so far; empty until something is done.
std::string ProgressBar::etaText(uint32_t done, uint32_t total, std::chrono::steady_clock::time_point now) const {
  if (done == 0 || done >= total) return "    ";
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const auto seconds = static_cast<uint64_t>(elapsed * static_cast<double>(total - done) / static_cast<double>(done));
  return " ETA " + (seconds >= 60 ? std::to_string(seconds / 60) + "m" : std::string()) + std::to_string(seconds % 60) + "s  ";
}

void ProgressBar::finish() {
  if (!drawn_) return;
  out_ << '\r' << std::string(label_.size() + kBarWidth + 40, ' ') << '\r' << std::flush;
  drawn_ = false;
}

}  // namespace fgb::harness
