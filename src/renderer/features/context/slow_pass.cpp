// debug.slow_pass=NAME:PERCENT (render_settings.hpp): the value is checked here, against the
// frame's passes, since which passes exist depends on the scene, the path and the other knobs.
#include "render_settings.hpp"

#include <fgb/core/error.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace fgb::features {

SlowPass slowPassOf(const std::string& value, const std::vector<std::string>& passes) {
  const std::string knob = "--set debug.slow_pass=" + value + ": ";
  const std::size_t colon = value.rfind(':');
  double percent = 0.0;
  const char* end = value.data() + value.size();
  const auto parsed = colon == std::string::npos ? std::from_chars_result{nullptr, std::errc::invalid_argument}
                                                 : std::from_chars(value.data() + colon + 1, end, percent);
  if (colon == std::string::npos || colon == 0 || parsed.ec != std::errc{} || parsed.ptr != end ||
      !std::isfinite(percent) || percent <= 0.0 || percent > 10000.0) {
    throw InputError(knob + "expected PASS:PERCENT with PERCENT a number in (0, 10000], e.g. \"Bloom:50\"");
  }
  SlowPass slow{value.substr(0, colon), percent / 100.0};
  if (std::find(passes.begin(), passes.end(), slow.pass) == passes.end()) {
    std::vector<std::string> unique;
    std::string known;
    for (const auto& name : passes) {
      if (std::find(unique.begin(), unique.end(), name) != unique.end()) continue;
      unique.push_back(name);
      known += (known.empty() ? "" : ", ") + name;
    }
    throw InputError(knob + "no pass '" + slow.pass + "' in this frame (passes: " + known + ")");
  }
  return slow;
}

}  // namespace fgb::features
