#include <fmt/format.h>

#include <algorithm>
#include <fgb/core/atomic_file.hpp>
#include <fgb/core/error.hpp>
#include <fgb/core/stopwatch.hpp>
#include <fgb/harness/base/json_io.hpp>
#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/report/report.hpp>
#include <fgb/harness/run/run_outputs.hpp>
#include <fstream>

namespace fgb::harness {
namespace {

ImageVerdict compareWithGoldenFile(const std::string& kind, const std::filesystem::path& goldenFile, const Image& rendered,
                                   const Thresholds& limits, const std::filesystem::path& diffPath, std::string& diffWritten,
                                   GoldenPictures* pictures) {
  const Image reference = readImage(goldenFile);
  if (reference.width != rendered.width || reference.height != rendered.height) {
    throw InputError(goldenFile.string() + ": golden is " + describeSize(reference) + " but the render is " +
                     describeSize(rendered) + " (re-bless or run at the golden's size)");
  }
  const Comparison comparison = compareImages(reference, rendered, metricOptionsFor(limits));
  ImageVerdict verdict = judgeImage(kind, comparison.metrics, limits);
  if (verdict.failures.empty() && !pictures) return verdict;
  Image heat = heatMap(comparison.errorMap, comparison.nonFiniteMask, reference.width, reference.height);
  if (!verdict.failures.empty()) {
    writePng(diffPath, heat);
    if (diffWritten.empty()) diffWritten = diffPath.string();
  }
  if (pictures) *pictures = GoldenPictures{reference, std::move(heat)};
  return verdict;
}

}  // namespace

namespace {

// report.html's strip: each compared pass's image beside its heat map, in declaration order, so the
// place where the difference enters shows.
std::vector<ReportImages::PassThumb> passStripOf(const PassLocalisation& localisation) {
  constexpr uint32_t kThumbWidth = 160;
  std::vector<ReportImages::PassThumb> strip;
  for (const PassImageVerdict& image : localisation.images) {
    // Marked where the difference enters: a differing image of a first-difference node.
    const bool first =
        image.differs && std::find(localisation.firstDifferences.begin(), localisation.firstDifferences.end(),
                                   image.pass) != localisation.firstDifferences.end();
    Image shown = image.test;
    if (image.content != render::CaptureContent::Color) {
      // Depth and ids as grey levels of their range, so the thumbnail shows shapes.
      float top = 0.0f;
      for (std::size_t i = 0; i < shown.pixelCount(); ++i) top = std::max(top, shown.rgba[i * 4]);
      for (std::size_t i = 0; i < shown.pixelCount(); ++i) {
        const float v = top > 0.0f ? shown.rgba[i * 4] / top : 0.0f;
        shown.rgba[i * 4] = shown.rgba[i * 4 + 1] = shown.rgba[i * 4 + 2] = v;
      }
    }
    strip.push_back(
        {image.pass, image.file, image.differs, first, encodePng(shrinkToWidth(shown, kThumbWidth)),
         image.heatMap.width ? encodePng(shrinkToWidth(image.heatMap, kThumbWidth)) : std::vector<uint8_t>{}});
  }
  return strip;
}

}  // namespace

void writeRunOutputs(const std::filesystem::path& dir, const RunArtifacts& a) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw InputError(dir.string() + ": cannot create the output directory (" + ec.message() + ")");
  }
  Stopwatch encoding;
  writeExr(dir / "frame.exr", a.images.hdr);
  ReportImages pictures;  // shown inline by report.html
  pictures.frame = encodePng(a.images.display);
  pictures.width = a.images.display.width;
  pictures.height = a.images.display.height;
  writeFileAtomic(dir / "frame.png", std::as_bytes(std::span(pictures.frame)));
  RunResult run = a.run;  // with the encoding time, which only now is known
  run.overhead.encodeMs = encoding.elapsedMs();
  if (a.golden.reference.width > 0) pictures.reference = encodePng(a.golden.reference);
  if (a.golden.heatMap.width > 0) pictures.heatMap = encodePng(a.golden.heatMap);
  for (const SlowFrame& slow : a.slowest) pictures.slowest.push_back({slow.frame, slow.pathTimeS, encodePng(slow.display)});
  for (const DebugViewImage& view : a.debugViews) {
    pictures.debugViews.push_back({view.view, encodePng(view.display)});
    writeFileAtomic(dir / ("debug-" + view.view + ".png"), std::as_bytes(std::span(pictures.debugViews.back().png)));
  }
  if (a.passes) writeCaptureSet(dir / "passes", *a.passes);
  if (a.localisation) pictures.passStrip = passStripOf(*a.localisation);
  writeFileAtomic(dir / "timings.json", dumpJson(toJson(run)));
  writeFileAtomic(dir / "timings.csv", toCsv(run));
  writeFileAtomic(dir / "graph.dot", a.graphBrief);
  writeFileAtomic(dir / "graph-full.dot", a.graphFull);
  writeFileAtomic(dir / "report.md", markdownReport(run));
  writeFileAtomic(dir / "report.html", htmlReport(run, pictures));
}

GoldenResult checkGolden(const Golden& golden, const RenderedImages& images, const std::filesystem::path& diffDir,
                         GoldenPictures* pictures) {
  GoldenResult result;
  result.file = golden.jsonPath.string();
  std::error_code ec;
  std::filesystem::create_directories(diffDir, ec);
  result.images.push_back(compareWithGoldenFile("display", golden.displayImage, quantizeToSrgb8(images.display),
                                                golden.display, diffDir / "golden-diff.png", result.diffImage, pictures));
  if (!golden.hdrImage.empty()) {
    result.images.push_back(compareWithGoldenFile("hdr", golden.hdrImage, quantizeToHalf(images.hdr), golden.hdr,
                                                  diffDir / "golden-diff-hdr.png", result.diffImage, nullptr));
  }
  bool failed = false;
  for (const auto& image : result.images) failed = failed || !image.failures.empty();
  result.verdict = failed ? "fail" : "pass";
  return result;
}

void localiseAgainstPassGoldens(const Golden& golden, RunArtifacts& artifacts) {
  const std::filesystem::path dir = passGoldenDir(golden.jsonPath);
  std::error_code ec;
  if (!artifacts.passes || !std::filesystem::is_regular_file(dir / "passes.json", ec)) return;
  PassLocalisation localisation = localise(readCaptureSet(dir), *artifacts.passes);
  localisation.goldenDir = dir.string();
  artifacts.run.firstDifference = localisation.line;
  artifacts.run.passesGolden = toJson(localisation);
  artifacts.localisation = std::move(localisation);
}

std::string sceneHash(const std::string& scenePath) {
  constexpr uint64_t kOffset = 14695981039346656037ull, kPrime = 1099511628211ull;
  uint64_t hash = kOffset;
  auto mix = [&](unsigned char byte) { hash = (hash ^ byte) * kPrime; };
  std::ifstream in(scenePath, std::ios::binary);
  if (in) {
    char buffer[4096];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
      for (std::streamsize i = 0; i < in.gcount(); ++i) mix(static_cast<unsigned char>(buffer[i]));
    }
  } else {
    for (char c : scenePath) mix(static_cast<unsigned char>(c));
  }
  return fmt::format("fnv1a64:{:016x}", hash);
}

}  // namespace fgb::harness
