// `fgbench compare A B`: image metrics between two EXR/PNG files (A is the reference), with an
// optional heat map. Fails (exit 1) the way idiff does: by default when any pixel has a channel
// differing by more than the per-channel threshold; --fail-percent allows a share of such pixels,
// and --max-flip-mean / --max-rmse judge by those metrics instead. NaN/Inf anywhere always fails.
#include "verb.hpp"

#include <fgb/core/error.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/metrics/metrics.hpp>

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <optional>

namespace fgb::app {
namespace {

struct CompareOptions {
  std::string reference, test, diff;
  double channelThreshold = -1.0;
  double pixelsPerDegree = harness::defaultPixelsPerDegree();
  bool noFlip = false;
  bool json = false;
  bool quiet = false;
  std::optional<double> failPercent, maxFlipMean, maxRmse;
};

void printMetrics(const harness::ImageMetrics& m) {
  std::cout << fmt::format("size                  {}x{} ({} values)\n", m.width, m.height, m.domain);
  std::cout << fmt::format("max abs error         {:.6g}\n", m.maxAbsError);
  std::cout << fmt::format("RMSE                  {:.6g}\n", m.rmse);
  std::cout << fmt::format("PSNR                  {} (peak {:g})\n",
                           std::isfinite(m.psnr) ? fmt::format("{:.3f} dB", m.psnr) : std::string("inf (identical)"), m.peak);
  std::cout << fmt::format("over {:.4g}/channel    {:.4f}% of pixels\n", m.channelThreshold, m.shareOverThreshold * 100.0);
  std::cout << fmt::format("NaN/Inf pixels        {} in A, {} in B\n", m.nonFiniteReference, m.nonFiniteTest);
  if (m.flip) {
    std::cout << fmt::format("FLIP ({})            mean {:.6f}  p50 {:.6f}  p95 {:.6f}  p99 {:.6f}  max {:.6f}\n", m.flip->mode,
                             m.flip->mean, m.flip->p50, m.flip->p95, m.flip->p99, m.flip->max);
    if (m.flip->mode == "hdr") {
      std::cout << fmt::format("HDR-FLIP exposures    {} from {:+.3f} to {:+.3f} stops\n", m.flip->exposures,
                               m.flip->startExposure, m.flip->stopExposure);
    }
  }
}

// The pixel criterion (idiff's): a pixel fails when any channel differs by more than the threshold,
// and the images differ when more than failPercent of the pixels fail (default 0: any pixel). It
// applies unless the user judges by a metric limit alone (--max-flip-mean / --max-rmse without
// --fail-percent), which is how those options loosen the default.
bool pixelCriterionApplies(const CompareOptions& o) { return o.failPercent || (!o.maxFlipMean && !o.maxRmse); }

std::string limitFailures(const harness::ImageMetrics& m, const CompareOptions& o) {
  std::string failures;
  if (m.hasNonFinite()) failures += fmt::format(" {} NaN/Inf pixels in A, {} in B;", m.nonFiniteReference, m.nonFiniteTest);
  const double allowedPercent = o.failPercent.value_or(0.0);
  if (pixelCriterionApplies(o) && m.shareOverThreshold * 100.0 > allowedPercent) {
    failures += fmt::format(" {:.4f}% of pixels differ by more than {:.4g} in a channel (allowed: {:g}%);",
                            m.shareOverThreshold * 100.0, m.channelThreshold, allowedPercent);
  }
  if (o.maxFlipMean && m.flip && m.flip->mean > *o.maxFlipMean) {
    failures += fmt::format(" FLIP mean {:.6f} > {:.6f};", m.flip->mean, *o.maxFlipMean);
  }
  if (o.maxRmse && m.rmse > *o.maxRmse) failures += fmt::format(" RMSE {:.6g} > {:.6g};", m.rmse, *o.maxRmse);
  return failures;
}

int compareVerb(const CompareOptions& o) {
  const auto [a, b] = harness::readImagePair(o.reference, o.test);
  if (a.width != b.width || a.height != b.height) {
    throw InputError(fmt::format("{} is {} but {} is {}: images must have the same size", o.reference,
                                 harness::describeSize(a), o.test, harness::describeSize(b)));
  }
  harness::MetricOptions metricOptions;
  metricOptions.channelThreshold = o.channelThreshold;
  metricOptions.pixelsPerDegree = o.pixelsPerDegree;
  metricOptions.flip = !o.noFlip;
  const harness::Comparison c = harness::compareImages(a, b, metricOptions);
  if (!o.diff.empty()) harness::writePng(o.diff, harness::heatMap(c.errorMap, c.nonFiniteMask, a.width, a.height));

  const std::string failures = limitFailures(c.metrics, o);
  if (o.json) {
    nlohmann::json j = harness::toJson(c.metrics);
    j["reference"] = o.reference;
    j["test"] = o.test;
    if (!o.diff.empty()) j["diff"] = o.diff;
    j["verdict"] = failures.empty() ? "same" : "differ";
    std::cout << harness::dumpJson(j);
  } else if (!o.quiet) {
    printMetrics(c.metrics);
  }
  if (!failures.empty()) throw CheckFailed(o.reference + " vs " + o.test + ":" + failures);
  return kExitOk;
}

static VerbRegistrar reg(30, [](CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* sub = app.add_subcommand("compare", "Image metrics (max abs, RMSE, PSNR, share over threshold, FLIP) between "
                                                "A and B; exit 0 same, 1 differ (any pixel over the threshold unless "
                                                "loosened), 2 bad input");
  sub->add_option("a", o->reference, "Reference image (EXR or PNG)")->required();
  sub->add_option("b", o->test, "Test image (EXR or PNG)")->required();
  sub->add_option("--diff", o->diff, "Write a heat map PNG of the per-pixel error (FLIP, or abs error with --no-flip)");
  sub->add_option("--threshold", o->channelThreshold, "Per-channel threshold: a pixel differs when any channel differs "
                                                      "by more (default 2/255 for PNG, 0.01 for EXR)")
      ->check(CLI::Range(0.0, 1e30));
  sub->add_option("--fail-percent", o->failPercent, "Exit 1 only when more than this percentage of pixels differ "
                                                    "(default 0: any differing pixel fails, as in idiff)")
      ->check(CLI::Range(0.0, 100.0));
  sub->add_option("--ppd", o->pixelsPerDegree, "FLIP observer: pixels per degree (default 67: 0.7 m wide 4K at 0.7 m)")
      ->check(CLI::Range(1.0, 1000.0));
  CLI::Option* noFlip = sub->add_flag("--no-flip", o->noFlip, "Skip FLIP");
  sub->add_option("--max-flip-mean", o->maxFlipMean, "Exit 1 when the mean FLIP error is above this; judges by this "
                                                     "instead of differing pixels unless --fail-percent is given too")
      ->check(CLI::Range(0.0, 1.0))
      ->excludes(noFlip);
  sub->add_option("--max-rmse", o->maxRmse, "Exit 1 when the RMSE is above this; judges by this instead of "
                                            "differing pixels unless --fail-percent is given too")
      ->check(CLI::Range(0.0, 1e30));
  sub->add_flag("--json", o->json, "Machine-readable output on stdout");
  sub->add_flag("--quiet", o->quiet, "No output unless failing");
  return Verb{sub, [o] { return compareVerb(*o); }};
});

}  // namespace
}  // namespace fgb::app
