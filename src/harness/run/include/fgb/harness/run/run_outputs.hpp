// What `fgbench run --out DIR` writes, and the golden check of a run's images. Every file is written
// atomically (temporary + rename), so a crash never leaves a half-written output.
#pragma once

#include <fgb/harness/image/image.hpp>
#include <fgb/harness/passes/pass_golden.hpp>
#include <fgb/harness/results/golden.hpp>
#include <fgb/harness/results/timings.hpp>
#include <filesystem>
#include <optional>
#include <string>

namespace fgb::harness {

struct RenderedImages {
  Image hdr;      // linear HDR before tone mapping
  Image display;  // tone-mapped, linear values in [0, 1]
};

// The golden's display image and the FLIP heat map of the render against it, for report.html.
struct GoldenPictures {
  Image reference;
  Image heatMap;
};

// One of the slowest frames along a camera path, rendered again alone (camera.time=T).
struct SlowFrame {
  std::size_t frame = 0;  // index among the measured frames
  double pathTimeS = 0.0;
  Image display;  // tone-mapped, as RenderedImages::display
};

// The measured view rendered again with a debug view of the clusters (RenderRequest::debugViews).
struct DebugViewImage {
  std::string view;  // debug.view's value: lod | clusters
  Image display;
};

struct RunArtifacts {
  RunResult run;
  RenderedImages images;
  std::vector<SlowFrame> slowest;  // RenderRequest::slowestFrames, slowest first (report thumbnails)
  std::vector<DebugViewImage> debugViews;  // RenderRequest::debugViews: debug-lod.png, debug-clusters.png
  std::string graphBrief, graphFull;
  GoldenPictures golden;  // empty (0x0) without --golden
  std::optional<PassCaptureSet> passes;          // --capture: the last frame's per-pass outputs
  std::optional<PassLocalisation> localisation;  // compared with per-pass goldens (frame golden failed)
};

// Creates DIR if needed (InputError when that is impossible) and writes frame.exr, frame.png,
// timings.json, timings.csv, graph.dot, graph-full.dot, report.md and report.html; with captures,
// DIR/passes/ (pass_capture.hpp).
void writeRunOutputs(const std::filesystem::path& dir, const RunArtifacts& artifacts);

// Compares the display image (as frame.png stores it) with the golden PNG and, when the golden has
// one, the HDR image (as frame.exr stores it) with the golden EXR. On failure writes heat maps
// golden-diff.png (display) / golden-diff-hdr.png into diffDir. Mismatched sizes or unreadable
// goldens -> InputError naming the file. `pictures`, when given, receives the display reference and
// its heat map whether or not the comparison failed.
GoldenResult checkGolden(const Golden& golden, const RenderedImages& images, const std::filesystem::path& diffDir,
                         GoldenPictures* pictures = nullptr);

// With per-pass goldens next to `golden` (passGoldenDir) and a capture: the first-difference
// verdict, also recorded in the run (firstDifference, passesGolden). Nothing when either is missing.
void localiseAgainstPassGoldens(const Golden& golden, RunArtifacts& artifacts);

// Stable content hash of a scene file (FNV-1a 64, hex); built-in scenes hash their name.
std::string sceneHash(const std::string& scenePath);

}  // namespace fgb::harness
