// Per-pass goldens and first-difference localisation (issue 29). A golden configuration
// golden/<scene>/<device-class>/<config>.json may have a folder <config>/passes/ holding a capture
// set (pass_capture.hpp) with, per image, thresholds from the noise between the bless renders, and
// per count a tolerance. When the frame differs, the run's captures are compared with it:
//
//   a node differs      when one of its images has more pixels off (any channel beyond the
//                       image's channel threshold) than its share threshold allows, or one of its
//                       counts moved beyond its tolerance;
//   a first difference  is a node that differs while every node it reads from (graph::dataInputs;
//                       through nodes with nothing captured, to theirs) matches.
//
// There may be several (parallel branches); all are named, with the nodes before them that match.
#pragma once

#include <fgb/harness/passes/pass_capture.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fgb::harness {

// <golden JSON's folder>/<config>/passes for a golden JSON file <config>.json.
std::filesystem::path passGoldenDir(const std::filesystem::path& goldenJson);

// The thresholds, noise and tolerances of a golden made from repeated captures of one
// configuration (the first is stored): per image the worst pixel share and channel difference
// between the first render and any other, per count the largest spread.
CaptureExtras passGoldenExtras(const std::vector<PassCaptureSet>& renders);

struct PassImageVerdict {
  std::string pass;
  std::string file;
  render::CaptureContent content = render::CaptureContent::Color;
  bool differs = false;
  double share = 0.0;  // pixels off beyond the channel threshold
  double allowedShare = 0.0;
  double maxAbs = 0.0;
  std::optional<double> flipMean;  // colour images that differ
  Image test;                      // the run's image and its heat map against the golden (report strip)
  Image heatMap;
};

struct PassStatVerdict {
  PassStat golden;
  double value = 0.0;
  bool differs = false;
};

struct PassLocalisation {
  std::string goldenDir;
  std::vector<PassImageVerdict> images;
  std::vector<PassStatVerdict> stats;
  std::vector<std::string> firstDifferences;  // node names, declaration order
  std::vector<std::string> matchingBefore;    // nodes before them (their ancestors) that match, in order
  std::vector<std::string> differing;         // every node that differs
  std::string line;                           // the one-line verdict
};

// Compares a run's captures with the golden set; the verdict names the first differences.
PassLocalisation localise(const LoadedCaptureSet& golden, const PassCaptureSet& test);

// timings.json "passes_golden".
nlohmann::json toJson(const PassLocalisation& localisation);

}  // namespace fgb::harness
