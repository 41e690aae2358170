#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fgb/harness/metrics/metrics.hpp>
#include <fgb/harness/passes/pass_golden.hpp>
#include <functional>
#include <map>
#include <set>

namespace fgb::harness {
namespace {

using render::CaptureContent;

// A channel differs beyond rounding: half floats of the HDR values (lavapipe is bit-exact, GPUs
// round differently), and exact values for depth and ids (which differ by 1 when they differ).
double defaultChannelThreshold(CaptureContent content) {
  return content == CaptureContent::Color ? 1e-3 : 1e-6;
}

struct Difference {
  double share = 0.0;
  double maxAbs = 0.0;
};

Difference differenceOf(const Image& reference, const Image& test, double channelThreshold) {
  MetricOptions options;
  options.channelThreshold = channelThreshold;
  options.flip = false;
  const ImageMetrics m = compareImages(reference, test, options).metrics;
  const double nonFinite =
      double(m.nonFiniteReference + m.nonFiniteTest) / double(std::max<std::size_t>(1, reference.pixelCount()));
  return {std::max(m.shareOverThreshold, nonFinite), m.maxAbsError};
}

const CapturedImage* findImage(const PassCaptureSet& set, const std::string& file) {
  for (const auto& image : set.images)
    if (image.file == file) return &image;
  return nullptr;
}

enum class Status { Unknown, Matches, Differs };

std::string quoted(const std::string& name) {
  return "\"" + name + "\"";
}

std::string percent(double share) {
  return fmt::format("{:.{}f}%", 100.0 * share, share < 0.001 ? 3 : 1);
}

std::string compactNumber(double value) {
  return fmt::format("{:g}", value);
}

// Why a node differs, in words: its worst image and its moved counts.
std::string detailOf(const PassLocalisation& l, const std::string& pass) {
  std::vector<std::string> parts;
  const PassImageVerdict* worst = nullptr;
  for (const auto& image : l.images)
    if (image.pass == pass && image.differs && (!worst || image.share > worst->share)) worst = &image;
  if (worst) {
    if (worst->flipMean)
      parts.push_back(fmt::format("FLIP {:.3f}, {} of pixels", *worst->flipMean, percent(worst->share)));
    else
      parts.push_back(fmt::format("{} {} of pixels, max {:.3g}", contentName(worst->content), percent(worst->share),
                                  worst->maxAbs));
  }
  for (const auto& stat : l.stats)
    if (stat.golden.pass == pass && stat.differs)
      parts.push_back(
          fmt::format("{} {} → {}", stat.golden.label, compactNumber(stat.golden.value), compactNumber(stat.value)));
  std::string out;
  for (const auto& part : parts) out += (out.empty() ? "" : ", ") + part;
  return out;
}

std::string identicalText(const std::vector<std::string>& names) {
  if (names.empty()) return "no captured pass before it";
  if (names.size() == 1) return quoted(names[0]) + " identical";
  if (names.size() == 2) return quoted(names[0]) + ", " + quoted(names[1]) + " identical";
  return fmt::format("{} … {} identical ({} passes)", quoted(names.front()), quoted(names.back()), names.size());
}

void judgeImages(const LoadedCaptureSet& golden, const PassCaptureSet& test, PassLocalisation& l) {
  const nlohmann::json& entries = golden.document.at("images");
  for (const CapturedImage& image : test.images) {
    const CapturedImage* reference = findImage(golden.set, image.file);
    if (!reference) continue;  // nothing to compare with: the node stays unknown
    PassImageVerdict verdict;
    verdict.pass = image.pass;
    verdict.file = image.file;
    verdict.content = image.content;
    double channel = defaultChannelThreshold(image.content);
    for (const auto& entry : entries) {
      if (!entry.is_object() || entry.value("file", "") != image.file) continue;
      const auto thresholds = entry.find("thresholds");
      if (thresholds == entry.end() || !thresholds->is_object()) continue;
      channel = thresholds->value("channel", channel);
      verdict.allowedShare = thresholds->value("share", 0.0);
    }
    if (reference->image.width != image.image.width || reference->image.height != image.image.height) {
      verdict.differs = true;
      verdict.share = 1.0;
    } else {
      const Difference d = differenceOf(reference->image, image.image, channel);
      verdict.share = d.share;
      verdict.maxAbs = d.maxAbs;
      verdict.differs = d.share > verdict.allowedShare;
      MetricOptions options;
      options.channelThreshold = channel;
      options.flip = verdict.differs && image.content == CaptureContent::Color;
      const Comparison c = compareImages(reference->image, image.image, options);
      if (c.metrics.flip) verdict.flipMean = c.metrics.flip->mean;
      verdict.heatMap = heatMap(c.errorMap, c.nonFiniteMask, image.image.width, image.image.height);
    }
    verdict.test = image.image;
    l.images.push_back(std::move(verdict));
  }
}

void judgeStats(const LoadedCaptureSet& golden, const PassCaptureSet& test, PassLocalisation& l) {
  for (const PassStat& reference : golden.set.stats) {
    const auto found =
        std::find_if(test.stats.begin(), test.stats.end(), [&](const PassStat& s) { return s.key == reference.key; });
    if (found == test.stats.end()) continue;
    l.stats.push_back({reference, found->value, std::abs(found->value - reference.value) > reference.tolerance});
  }
}

}  // namespace

std::filesystem::path passGoldenDir(const std::filesystem::path& goldenJson) {
  return goldenJson.parent_path() / goldenJson.stem() / "passes";
}

CaptureExtras passGoldenExtras(const std::vector<PassCaptureSet>& renders) {
  CaptureExtras extras;
  const PassCaptureSet& first = renders.front();
  for (const CapturedImage& image : first.images) {
    const double channel = defaultChannelThreshold(image.content);
    Difference noise;
    for (std::size_t k = 1; k < renders.size(); ++k) {
      const CapturedImage* other = findImage(renders[k], image.file);
      if (!other || other->image.width != image.image.width || other->image.height != image.image.height) continue;
      const Difference d = differenceOf(image.image, other->image, channel);
      noise.share = std::max(noise.share, d.share);
      noise.maxAbs = std::max(noise.maxAbs, d.maxAbs);
    }
    // Three times the share of pixels that moved between identical renders (0 where none did:
    // lavapipe is bit-exact, so any moved pixel is a difference).
    extras.images[image.file] = {{"thresholds", {{"channel", channel}, {"share", std::min(1.0, 3.0 * noise.share)}}},
                                 {"noise", {{"share", noise.share}, {"max_abs", noise.maxAbs}}}};
  }
  for (const PassStat& stat : first.stats) {
    double spread = 0.0;
    for (std::size_t k = 1; k < renders.size(); ++k)
      for (const PassStat& other : renders[k].stats)
        if (other.key == stat.key) spread = std::max(spread, std::abs(other.value - stat.value));
    extras.statTolerances[stat.key] = spread;
  }
  return extras;
}

PassLocalisation localise(const LoadedCaptureSet& golden, const PassCaptureSet& test) {
  PassLocalisation l;
  judgeImages(golden, test, l);
  judgeStats(golden, test, l);

  const auto& nodes = test.nodes;
  std::vector<Status> status(nodes.size(), Status::Unknown);
  std::map<std::string, std::size_t> indexOf;
  for (std::size_t i = 0; i < nodes.size(); ++i) indexOf[nodes[i].name] = i;
  const auto mark = [&](const std::string& pass, bool differs) {
    const auto found = indexOf.find(pass);
    if (found == indexOf.end()) return;
    Status& s = status[found->second];
    s = differs ? Status::Differs : (s == Status::Differs ? Status::Differs : Status::Matches);
  };
  for (const auto& image : l.images) mark(image.pass, image.differs);
  for (const auto& stat : l.stats) mark(stat.golden.pass, stat.differs);

  // A node's inputs that say something: through nodes with nothing compared, to their inputs.
  std::vector<std::optional<std::set<std::size_t>>> known(nodes.size());
  std::function<const std::set<std::size_t>&(std::size_t)> inputsOf =
      [&](std::size_t node) -> const std::set<std::size_t>& {
    if (!known[node]) {
      std::set<std::size_t> inputs;
      for (const uint32_t input : nodes[node].inputs) {
        if (input >= nodes.size() || input >= node) continue;  // declaration order: inputs come first
        if (status[input] != Status::Unknown)
          inputs.insert(input);
        else
          for (const std::size_t further : inputsOf(input)) inputs.insert(further);
      }
      known[node] = std::move(inputs);
    }
    return *known[node];
  };
  std::set<std::size_t> before;
  std::function<void(std::size_t)> collect = [&](std::size_t node) {
    for (const std::size_t input : inputsOf(node))
      if (status[input] == Status::Matches && before.insert(input).second) collect(input);
  };
  for (std::size_t node = 0; node < nodes.size(); ++node) {
    if (status[node] != Status::Differs) continue;
    l.differing.push_back(nodes[node].name);
    const auto& inputs = inputsOf(node);
    if (std::all_of(inputs.begin(), inputs.end(), [&](std::size_t i) { return status[i] == Status::Matches; })) {
      l.firstDifferences.push_back(nodes[node].name);
      collect(node);
    }
  }
  for (const std::size_t node : before) l.matchingBefore.push_back(nodes[node].name);

  if (l.firstDifferences.empty()) {
    l.line = l.differing.empty() ? "no captured pass differs from its golden"
                                 : "passes differ but none has all its inputs matching";
  } else {
    std::string named;
    for (const auto& pass : l.firstDifferences) {
      const std::string detail = detailOf(l, pass);
      named += (named.empty() ? "" : ", ") + quoted(pass) + (detail.empty() ? "" : " (" + detail + ")");
    }
    l.line = fmt::format("first difference{} at {}; {}", l.firstDifferences.size() > 1 ? "s" : "", named,
                         identicalText(l.matchingBefore));
  }
  return l;
}

nlohmann::json toJson(const PassLocalisation& l) {
  nlohmann::json images = nlohmann::json::array();
  for (const auto& image : l.images) {
    nlohmann::json entry{{"pass", image.pass},
                         {"file", image.file},
                         {"differs", image.differs},
                         {"share", image.share},
                         {"allowed_share", image.allowedShare},
                         {"max_abs", image.maxAbs}};
    if (image.flipMean) entry["flip_mean"] = *image.flipMean;
    images.push_back(std::move(entry));
  }
  nlohmann::json stats = nlohmann::json::array();
  for (const auto& stat : l.stats)
    stats.push_back({{"key", stat.golden.key},
                     {"pass", stat.golden.pass},
                     {"golden", stat.golden.value},
                     {"value", stat.value},
                     {"tolerance", stat.golden.tolerance},
                     {"differs", stat.differs}});
  return {{"golden", l.goldenDir},
          {"verdict", l.line},
          {"first_differences", l.firstDifferences},
          {"matching_before", l.matchingBefore},
          {"differing", l.differing},
          {"images", images},
          {"stats", stats}};
}

}  // namespace fgb::harness
