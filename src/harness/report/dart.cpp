#include <fgb/harness/report/dart.hpp>

#include <fgb/harness/report/report.hpp>

#include <fmt/format.h>

#include <cmath>

namespace fgb::harness {

std::string dartMeasurement(const std::string& name, double value) {
  return fmt::format(R"(<DartMeasurement name="{}" type="numeric/double">{:.6g}</DartMeasurement>)", escapeXml(name),
                     std::isfinite(value) ? value : 0.0) + "\n";
}

std::string dartMeasurementFile(const std::string& name, const std::string& path, const std::string& mime) {
  return fmt::format(R"(<DartMeasurementFile name="{}" type="{}">{}</DartMeasurementFile>)", escapeXml(name), mime,
                     escapeXml(path)) + "\n";
}

std::string dartMeasurements(const RunResult& run) {
  std::string out;
  for (const auto& p : run.passes) {
    if (!p.culled) out += dartMeasurement("gpu_ms " + p.name, p.gpu.median);
  }
  out += dartMeasurement("frame_gpu_ms", run.frameGpu.median);
  out += dartMeasurement("frame_cpu_ms", run.frameCpu.median);
  if (run.golden) {
    for (const auto& image : run.golden->images) {
      const auto& m = image.metrics;
      out += dartMeasurement(image.kind + " rmse", m.rmse);
      out += dartMeasurement(image.kind + " max_abs_error", m.maxAbsError);
      if (std::isfinite(m.psnr)) out += dartMeasurement(image.kind + " psnr_db", m.psnr);
      out += dartMeasurement(image.kind + " share_over_threshold", m.shareOverThreshold);
      if (m.flip) {
        out += dartMeasurement(image.kind + " flip_mean", m.flip->mean);
        out += dartMeasurement(image.kind + " flip_p99", m.flip->p99);
      }
    }
    if (run.golden->verdict == "fail" && !run.golden->diffImage.empty()) out += dartMeasurementFile("diff", run.golden->diffImage);
    if (!run.firstDifference.empty()) {
      out += fmt::format(R"(<DartMeasurement name="first difference" type="text/string">{}</DartMeasurement>)",
                         escapeXml(run.firstDifference)) +
             "\n";
    }
  }
  return out;
}

}  // namespace fgb::harness
