// runStress: the baseline twice (its noise), then every rung, one device at a time; verdicts.
#include <fmt/format.h>

#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/harness/stress/stress.hpp>

namespace fgb::harness {
namespace {

render::WorkloadConfig rungConfig(const StressPlan& plan, const StressRung& rung) {
  render::WorkloadConfig config = plan.base;
  for (const auto& [key, value] : rung.knobs) config.knobs[key] = value;
  if (rung.width) config.width = rung.width;
  if (rung.height) config.height = rung.height;
  config.checkFinite = true;
  return config;
}

// Renders a rung up to the compared frame and keeps its images and per-pass finiteness. A device
// failure (out of memory, device lost) is the rung's failure; bad input stays bad input.
StressRungOutcome renderRung(const WorkloadOpener& open, const StressPlan& plan, const StressRung& rung,
                             render::DeviceDescription* device) {
  StressRungOutcome outcome;
  outcome.rung = rung;
  try {
    ConfigurationRenderer renderer(open, rungConfig(plan, rung));
    renderer.warmUp(std::max(plan.imageFrame, 1u));
    outcome.images = renderer.readImages();
    outcome.nonFinite = renderer.workload().nonFiniteCounts();
    if (device) *device = renderer.workload().device();
    outcome.rendered = true;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& error) {
    outcome.error = error.what();
  }
  return outcome;
}

Comparison compareDisplays(const RenderedImages& baseline, const RenderedImages& rung) {
  return compareImages(quantizeToSrgb8(baseline.display), quantizeToSrgb8(rung.display));
}

std::string firstNonFiniteText(const std::vector<render::NonFiniteCounts>& counts, bool overHalfMax) {
  for (const auto& c : counts) {
    if (c.nan + c.inf == 0 && !(overHalfMax && c.overHalfMax > 0)) continue;
    return fmt::format("non-finite values in {} (NaN {}, Inf {}, > 32752 {})", c.pass, c.nan, c.inf, c.overHalfMax);
  }
  return "";
}

double flipMean(const ImageMetrics& m) {
  return m.flip ? m.flip->mean : 0.0;
}

}  // namespace

void judgeRung(StressRungOutcome& rung, const StressLadder& ladder, const ImageMetrics& noise) {
  const StressThresholds& t = ladder.thresholds;
  rung.pass = true;
  rung.failure.clear();
  auto fail = [&](std::string why) {
    if (rung.pass) rung.failure = std::move(why);
    rung.pass = false;
  };
  if (!rung.rendered) fail("did not render: " + rung.error);
  if (t.nonFinite) {
    if (const std::string text = firstNonFiniteText(rung.nonFinite, t.overHalfMax); !text.empty()) fail(text);
  }
  if (!ladder.compareImages || !rung.display) return;
  const ImageMetrics& m = *rung.display;
  if (m.hasNonFinite()) fail(fmt::format("{} non-finite pixels in the display image", m.nonFiniteTest));
  if (flipMean(m) - flipMean(noise) > t.flipMean) {
    fail(fmt::format("FLIP mean = {:.4g} > {:.4g} + noise {:.4g}", flipMean(m), t.flipMean, flipMean(noise)));
  }
  if (m.shareOverThreshold - noise.shareOverThreshold > t.pixelShare) {
    fail(fmt::format("pixels over 2/255 = {:.2f}% > {:.2f}% + noise {:.2f}%", 100 * m.shareOverThreshold,
                     100 * t.pixelShare, 100 * noise.shareOverThreshold));
  }
  if (m.maxAbsError > t.maxAbs) fail(fmt::format("max abs error = {:.4g} > {:.4g}", m.maxAbsError, t.maxAbs));
}

StressResult runStress(const WorkloadOpener& open, const StressPlan& plan, const StressProgress& progress) {
  Stopwatch clock;
  StressResult result;
  result.scene = plan.scene;
  result.ladder = plan.ladder;
  const auto& rungs = plan.ladder.rungs;
  if (rungs.size() < 2) throw InputError("--ladder: expected a baseline and at least one more rung");

  if (progress) progress(0, rungs.size(), rungs[0].value + " (baseline, twice)");
  StressRungOutcome baseline = renderRung(open, plan, rungs[0], &result.device);
  if (!baseline.rendered)
    throw DeviceError("the baseline rung " + rungs[0].value + " did not render: " + baseline.error);
  const StressRungOutcome again = renderRung(open, plan, rungs[0], nullptr);
  if (!again.rendered)
    throw DeviceError("the baseline rung " + rungs[0].value + " did not render twice: " + again.error);
  result.noise = compareDisplays(baseline.images, again.images).metrics;

  result.rungs.push_back(std::move(baseline));
  for (size_t i = 1; i < rungs.size(); ++i) {
    if (progress) progress(i, rungs.size(), rungs[i].value);
    StressRungOutcome rung = renderRung(open, plan, rungs[i], nullptr);
    const RenderedImages& base = result.rungs.front().images;
    const bool sameSize = rung.rendered && rung.images.display.width == base.display.width &&
                          rung.images.display.height == base.display.height;
    if (plan.ladder.compareImages && sameSize) {
      const Comparison comparison = compareDisplays(base, rung.images);
      rung.display = comparison.metrics;
      rung.heatMap =
          heatMap(comparison.errorMap, comparison.nonFiniteMask, rung.images.display.width, rung.images.display.height);
    }
    result.rungs.push_back(std::move(rung));
  }
  for (auto& rung : result.rungs) judgeRung(rung, result.ladder, result.noise);
  result.wallMs = clock.elapsedMs();
  return result;
}

std::optional<std::size_t> StressResult::firstFailure() const {
  for (std::size_t i = 0; i < rungs.size(); ++i)
    if (!rungs[i].pass) return i;
  return std::nullopt;
}

std::string StressResult::summary() const {
  const auto first = firstFailure();
  if (!first) return "stable through " + rungs.back().rung.value;
  const std::string failure = "first failure at " + rungs[*first].rung.value + ": " + rungs[*first].failure;
  if (*first == 0) return "unstable at the baseline " + failure.substr(std::string("first failure at ").size());
  return "stable up to " + rungs[*first - 1].rung.value + "; " + failure;
}

}  // namespace fgb::harness
