// Human reports of a run: report.md and a single-file report.html with inline SVG charts.
#pragma once

#include <fgb/harness/results/timings.hpp>

#include <cstdint>
#include <string>
#include <span>
#include <vector>

namespace fgb::harness {

// Pictures report.html shows inline (data: URIs), each the bytes of a PNG file; empty ones are left
// out. With a golden, the reference, this run's frame and the FLIP heat map between them appear
// side by side, with a toggle that flips one view between reference and test.
struct ReportImages {
  std::vector<uint8_t> frame;      // frame.png
  std::vector<uint8_t> reference;  // the golden's display image
  std::vector<uint8_t> heatMap;    // FLIP heat map of frame against reference
  uint32_t width = 0, height = 0;
  // Along a camera path: the slowest frames rendered alone (PNG), slowest first, with their
  // measured-frame index and path time.
  struct SlowFrame {
    std::size_t frame = 0;
    double pathTimeS = 0.0;
    std::vector<uint8_t> png;
  };
  std::vector<SlowFrame> slowest;
  // On a path that draws clusters: the frame with debug.view=lod and =clusters (debug-VIEW.png).
  struct DebugView {
    std::string view;
    std::vector<uint8_t> png;
  };
  std::vector<DebugView> debugViews;
  // Per-pass goldens compared (the frame golden failed): each pass's image and its heat map against
  // its golden, in declaration order; the first differences marked.
  struct PassThumb {
    std::string pass;
    std::string file;
    bool differs = false;
    bool firstDifference = false;
    std::vector<uint8_t> png;
    std::vector<uint8_t> heatMap;
  };
  std::vector<PassThumb> passStrip;
};

std::string markdownReport(const RunResult& run);
std::string htmlReport(const RunResult& run, const ReportImages& images = {});

// The charts, each a standalone <svg> element (exposed for tests and for embedding elsewhere).
std::string passBarsSvg(const RunResult& run);        // per-pass median (p5–p95) against budget
std::string frameSeriesSvg(const RunResult& run);     // per-frame GPU and CPU time
std::string queueTimelineSvg(const RunResult& run);   // per-queue lanes of passes in one frame

// The sentence every report carries when the device's timestamps are the host clock (lavapipe).
std::string timestampSourceNote(const render::DeviceDescription& device);
// Host time around rendering (start-up and its phases, loop overhead, readback, encoding), apart
// from GPU time; the same sentence in both reports.
std::string hostOverheadNote(const RunResult& run);
// What span, isolated cost and critical-path share mean (the calibration's frames), in both reports.
std::string isolatedCostNote(const RunResult& run);
// The span against the wall time per frame, and the device's clocks (where sampled), in words.
std::string wallClockNote(const RunResult& run);
// What async compute saved (render.async=0 against 1), how long the queues overlapped, and the
// one-queue frame's idle gaps against the isolated costs' sum; "" when the run did not compare.
std::string asyncComputeNote(const RunResult& run);

std::string escapeXml(const std::string& text);
std::string msaaLabel(uint32_t msaa);  // "4", or "scene default" for 0

}  // namespace fgb::harness
