#include <fgb/harness/report/html_util.hpp>

#include <fgb/harness/image/image_io.hpp>
#include <fgb/harness/report/report.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fgb::harness {

std::string base64(std::span<const uint8_t> bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    uint32_t chunk = 0;
    for (std::size_t k = 0; k < 3; ++k) chunk = chunk << 8 | (k < n ? bytes[i + k] : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(chunk >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

std::string pngDataUri(std::span<const uint8_t> png) { return "data:image/png;base64," + base64(png); }

std::string imgTag(const Image& image, const std::string& alt, uint32_t maxWidth) {
  const Image thumb = shrinkToWidth(image, maxWidth);
  return fmt::format(R"(<img src="{}" width="{}" height="{}" alt="{}">)",
                     pngDataUri(encodePng(thumb)), thumb.width, thumb.height, escapeXml(alt));
}

double LogAxis::at(double v, double from, double to) const {
  const double t = (std::log10(std::max(v, lo)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
  return from + t * (to - from);
}

namespace {

// 1, 2, 5 x 10^k: the values a log axis labels.
double nextStepUp(double v) {
  const double power = std::pow(10.0, std::floor(std::log10(v) + 1e-9));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * power > v * (1 + 1e-9)) return m * power;
  }
  return 10.0 * power;
}

double nextStepDown(double v) {
  const double power = std::pow(10.0, std::ceil(std::log10(v) - 1e-9));
  for (double m : {1.0, 0.5, 0.2, 0.1}) {
    if (m * power < v * (1 - 1e-9)) return m * power;
  }
  return 0.1 * power;
}

// `v` with `significant` significant digits in plain decimal notation (never an exponent), trailing
// zeros dropped: 0.0005, 2.5, 380, 12000.
std::string plainNumber(double v, int significant) {
  if (v == 0 || !std::isfinite(v)) return fmt::format("{}", v);
  const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(v))));
  const int decimals = std::max(0, significant - 1 - magnitude);
  std::string text = fmt::format("{:.{}f}", v, decimals);
  if (text.find('.') != std::string::npos) {
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
  }
  return text;
}

}  // namespace

std::vector<double> LogAxis::ticks() const {
  std::vector<double> out;
  for (int e = static_cast<int>(std::floor(std::log10(lo))); e <= static_cast<int>(std::ceil(std::log10(hi))); ++e) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, e);
      if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push_back(v);
    }
  }
  return out;
}

std::vector<double> LogAxis::minorTicks() const {
  std::vector<double> out;
  for (int e = static_cast<int>(std::floor(std::log10(lo))); e <= static_cast<int>(std::ceil(std::log10(hi))); ++e) {
    for (double m : {3.0, 4.0, 6.0, 7.0, 8.0, 9.0}) {
      const double v = m * std::pow(10.0, e);
      if (v >= lo && v <= hi) out.push_back(v);
    }
  }
  return out;
}

LogAxis paddedLogAxis(double lo, double hi) {
  if (!(lo > 0)) lo = 1e-6;
  if (!(hi > lo)) hi = lo * 1.0001;
  // At least a factor 1.5 across, centred on the data, so close points do not fill the whole plot.
  const double centre = std::sqrt(lo * hi);
  const double half = std::max(std::sqrt(hi / lo), std::sqrt(1.5)) * 1.08;
  LogAxis axis{centre / half, centre * half};
  // At least two labelled (1-2-5) ticks: widen towards the nearer of the next ones outside.
  while (axis.ticks().size() < 2) {
    const double up = nextStepUp(axis.hi), down = nextStepDown(axis.lo);
    if (up / axis.hi <= axis.lo / down) {
      axis.hi = up;
    } else {
      axis.lo = down;
    }
  }
  return axis;
}

std::string tickLabel(double v) { return plainNumber(v, 3); }

std::string durationLabel(double ms, int significant) {
  if (ms >= 1000.0) return plainNumber(ms / 1000.0, significant) + " s";
  if (ms >= 0.1) return plainNumber(ms, significant) + " ms";
  return plainNumber(ms * 1000.0, significant) + " µs";
}

}  // namespace fgb::harness
