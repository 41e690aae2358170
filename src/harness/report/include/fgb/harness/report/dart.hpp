// CTest/CDash measurements: tags in a test's output that CDash shows next to the test
// (<DartMeasurement> for numbers, <DartMeasurementFile> for images).
#pragma once

#include <fgb/harness/results/timings.hpp>

#include <string>

namespace fgb::harness {

std::string dartMeasurement(const std::string& name, double value);
std::string dartMeasurementFile(const std::string& name, const std::string& path, const std::string& mime = "image/png");

// Per-pass medians, frame times and (if compared) the golden's image metrics; the diff image as a
// file measurement when the golden failed.
std::string dartMeasurements(const RunResult& run);

}  // namespace fgb::harness
