#include <bit>
#include <cstdio>
#include <fgb/graph/barrier_names.hpp>
#include <iterator>

namespace fgb::graph {
namespace {

// Bit i of a mask is named kStageBitNames[i] / kAccessBitNames[i] (types.hpp numbers the bits in
// this order, from 1u << 0).
constexpr std::string_view kStageBitNames[] = {"draw-indirect",
                                               "vertex-input",
                                               "vertex",
                                               "fragment",
                                               "early-fragment-tests",
                                               "late-fragment-tests",
                                               "color-output",
                                               "compute",
                                               "transfer",
                                               "resolve",
                                               "host",
                                               "all-commands"};
static_assert(std::size(kStageBitNames) == std::bit_width(uint32_t{kStageAllCommands}));

constexpr std::string_view kAccessBitNames[] = {"indirect-read",  "index-read",   "vertex-read",   "uniform-read",
                                                "sampled-read",   "storage-read", "storage-write", "color-read",
                                                "color-write",    "depth-read",   "depth-write",   "transfer-read",
                                                "transfer-write", "host-read",    "host-write"};
static_assert(std::size(kAccessBitNames) == std::bit_width(uint32_t{kAccessHostWrite}));

constexpr std::string_view kLayoutNames[] = {
    "undefined",        "general",      "color-attachment", "depth-stencil-attachment", "depth-stencil-read-only",
    "shader-read-only", "transfer-src", "transfer-dst"};
static_assert(std::size(kLayoutNames) == static_cast<size_t>(Layout::TransferDst) + 1);

// Names of the set bits joined by '+'; bits without a name (none today) are kept as hex, so a new
// bit can never vanish from the dump.
template <size_t N>
std::string bitNames(uint32_t mask, const std::string_view (&names)[N]) {
  if (mask == 0) return "none";
  std::string out;
  for (size_t i = 0; i < N; ++i) {
    const uint32_t bit = 1u << i;
    if ((mask & bit) == 0) continue;
    if (!out.empty()) out += '+';
    out += names[i];
    mask &= ~bit;
  }
  if (mask != 0) {
    char unknown[16];
    std::snprintf(unknown, sizeof unknown, "0x%x", mask);
    if (!out.empty()) out += '+';
    out += unknown;
  }
  return out;
}

}  // namespace

std::string stageNames(StageMask stages) {
  return bitNames(stages, kStageBitNames);
}
std::string accessNames(AccessMask access) {
  return bitNames(access, kAccessBitNames);
}

std::string_view layoutName(Layout layout) {
  const auto index = static_cast<size_t>(layout);
  return index < std::size(kLayoutNames) ? kLayoutNames[index] : "?";
}

std::string describeBarrier(const Barrier& b, std::string_view resourceName, bool isTexture) {
  static constexpr std::string_view kArrow = " \u2192 ";
  std::string s;
  if (b.kind == Barrier::Kind::Release) s += "release ";
  if (b.kind == Barrier::Kind::Acquire) s += "acquire ";
  s += resourceName;
  s += ": " + stageNames(b.srcStages) + std::string(kArrow) + stageNames(b.dstStages);
  s += ", " + accessNames(b.srcAccess) + std::string(kArrow) + accessNames(b.dstAccess);
  if (isTexture)
    s += ", " + std::string(layoutName(b.oldLayout)) + std::string(kArrow) + std::string(layoutName(b.newLayout));
  if (b.srcQueue != b.dstQueue)
    s += ", queue " + std::to_string(b.srcQueue) + std::string(kArrow) + std::to_string(b.dstQueue);
  return s;
}

}  // namespace fgb::graph
