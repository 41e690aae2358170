// Per-pass captures (`fgbench run --capture passes`): the last frame's output images of each node
// and the culling counts, written to <out>/passes/ and stored as per-pass goldens by
// `fgbench bless --passes` in the same layout (pass_golden.hpp):
//
//   <node>[-<resource>].exr   colour: half RGBA; depth: 32-bit float R; visibility: 32-bit float
//                             R depth, G draw index, B triangle (canonical: no list slots)
//   <node>-<resource>.png     visibility only: false colour by draw index (to look at)
//   passes.json               the nodes with their data inputs (the graph's edges), the images,
//                             and in goldens each image's thresholds and measured noise
//   stats.json                the counts buffer-only nodes produce, each with the node it names
#pragma once

#include <fgb/harness/image/image.hpp>
#include <fgb/renderer/workload.hpp>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fgb::harness {

struct CapturedImage {
  std::string pass;
  std::string resource;
  render::CaptureContent content = render::CaptureContent::Color;
  std::string file;  // file name in the capture folder
  Image image;       // quantised as the file stores it (colour: half floats), so files compare exactly
};

// A count a node produces (buffer-only nodes have no image: their counts stand for them).
struct PassStat {
  std::string key;    // the run's stats key, "instances_visible"
  std::string label;  // "visible instances"
  std::string pass;   // "Mesh Frustum Cull"
  double value = 0.0;
  double tolerance = 0.0;  // goldens: the largest legitimate difference (run-to-run spread)
};

struct PassCaptureSet {
  std::vector<render::PassNode> nodes;  // declaration order, with data inputs
  std::vector<CapturedImage> images;    // declaration order of their nodes
  std::vector<PassStat> stats;
};

// The run's captures as files will hold them: names made unique per node (the resource appended
// when a node wrote several images), the counts picked from the run's stats by their owners.
PassCaptureSet makeCaptureSet(std::vector<render::PassCapture> captures, std::vector<render::PassNode> nodes,
                              const std::map<std::string, double>& runStats);

// What a golden adds to a capture: per image (by file name) fields of its passes.json entry
// (thresholds, noise), per stat its tolerance, and how it was made.
struct CaptureExtras {
  std::map<std::string, nlohmann::json> images;
  std::map<std::string, double> statTolerances;
  nlohmann::json made;
};

// Writes the images, passes.json and stats.json into `dir` (created; each file atomically, the
// images before the files that refer to them).
void writeCaptureSet(const std::filesystem::path& dir, const PassCaptureSet& set, const CaptureExtras& extras = {});

// The set in `dir`, with passes.json's entries as written (InputError naming the file otherwise).
struct LoadedCaptureSet {
  PassCaptureSet set;
  nlohmann::json document;  // passes.json
};
LoadedCaptureSet readCaptureSet(const std::filesystem::path& dir);

// --capture VALUE: "passes" (every node) or node names separated by commas; empty names are bad
// input (InputError naming the option).
std::vector<std::string> parseCaptureList(const std::string& value);

std::string contentName(render::CaptureContent content);  // "color" | "depth" | "visibility"

}  // namespace fgb::harness
