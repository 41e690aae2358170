#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fgb/harness/html_util.hpp>
#include <fgb/harness/image_io.hpp>
#include <fgb/harness/report.hpp>

namespace fgb::harness {

std::string imgTag(const Image& image, const std::string& alt, uint32_t maxWidth) {
  const Image thumb = shrinkToWidth(image, maxWidth);
  return fmt::format(R"(<img src="data:image/png;base64,{}" width="{}" height="{}" alt="{}">)",
                     base64(encodePng(thumb)), thumb.width, thumb.height, escapeXml(alt));
}

double LogAxis::at(double v, double from, double to) const {
  const double t = (std::log10(std::max(v, lo)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
  return from + t * (to - from);
}

std::vector<double> LogAxis::ticks() const {
  std::vector<double> out;
  for (int e = static_cast<int>(std::floor(std::log10(lo))); e <= static_cast<int>(std::ceil(std::log10(hi))); ++e) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, e);
      if (v >= lo && v <= hi) out.push_back(v);
    }
  }
  if (out.size() < 2) out = {lo, std::sqrt(lo * hi), hi};
  return out;
}

LogAxis paddedLogAxis(double lo, double hi) {
  if (!(lo > 0)) lo = 1e-6;
  if (!(hi > lo)) hi = lo * 1.0001;
  // At least a factor 1.5 across, centred on the data, so close points do not fill the whole plot.
  const double centre = std::sqrt(lo * hi);
  const double half = std::max(std::sqrt(hi / lo), std::sqrt(1.5)) * 1.08;
  return {centre / half, centre * half};
}

std::string tickLabel(double v) {
  return fmt::format("{:.3g}", v);
}

}  // namespace fgb::harness
