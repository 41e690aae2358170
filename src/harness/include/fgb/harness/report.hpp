// Human reports of a run: report.md and a single-file report.html with inline SVG charts.
#pragma once

#include <fgb/harness/timings.hpp>

#include <string>

namespace fgb::harness {

std::string markdownReport(const RunResult& run);
std::string htmlReport(const RunResult& run);

// The charts, each a standalone <svg> element (exposed for tests and for embedding elsewhere).
std::string passBarsSvg(const RunResult& run);        // per-pass median (p5–p95) against budget
std::string frameSeriesSvg(const RunResult& run);     // per-frame GPU and CPU time
std::string queueTimelineSvg(const RunResult& run);   // per-queue lanes of passes in one frame

// The sentence every report carries when the device's timestamps are the host clock (lavapipe).
std::string timestampSourceNote(const render::DeviceDescription& device);
// Host time around rendering (start-up and its phases, loop overhead, readback, encoding), apart
// from GPU time; the same sentence in both reports.
std::string hostOverheadNote(const RunResult& run);

std::string escapeXml(const std::string& text);
std::string msaaLabel(uint32_t msaa);  // "4", or "scene default" for 0

}  // namespace fgb::harness
