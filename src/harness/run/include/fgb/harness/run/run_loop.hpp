// The measurement loop: warm-up frames, then N measured frames, collecting per-pass GPU times and
// CPU frame times from a Workload. Independent of Vulkan (unit-tested with a fake Workload).
#pragma once

#include <fgb/harness/results/timings.hpp>
#include <fgb/renderer/workload.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace fgb::harness {

struct RunOptions {
  uint32_t warmup = 8;
  uint32_t frames = 64;
  double unstableSpread = kDefaultUnstableSpread;
  // Called after every rendered frame with (frames rendered, total to render); may be empty.
  std::function<void(uint32_t done, uint32_t total)> progress;
};

// Renders warmup + frames frames. Timings may arrive late (renderFrame returning a timing without
// passes means "none ready yet"; finish() returns the rest); the first `warmup` timings are
// dropped. Fills device, stats, passes, frame samples, summaries and the harness overhead; the
// caller fills scene, config and version. Throws DeviceError if the workload returned fewer
// timings than frames rendered.
RunResult runBenchmark(render::Workload& workload, const RunOptions& options);

// "--set key=value" arguments as a map; a malformed one is InputError naming it.
std::map<std::string, std::string> parseKnobs(const std::vector<std::string>& assignments);

}  // namespace fgb::harness
