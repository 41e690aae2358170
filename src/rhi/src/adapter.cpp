#include <fgb/core/error.hpp>
#include <fgb/rhi/device.hpp>
#include <string>

namespace fgb::rhi {

void checkRenderSize(const AdapterInfo& adapter, uint32_t width, uint32_t height) {
  const uint32_t limit = adapter.maxImageDimension2D;
  if (limit == 0 || (width <= limit && height <= limit)) return;
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string largest = std::to_string(limit) + "x" + std::to_string(limit);
  throw InputError("--width/--height: " + size + " is larger than the largest image " + adapter.name + " supports, " +
                   largest);
}

}  // namespace fgb::rhi
