#include <array>
#include <cstdio>
#include <fgb/graph/barrier_names.hpp>
#include <utility>

namespace fgb::graph {
namespace {

using BitName = std::pair<uint32_t, std::string_view>;

constexpr std::array kStageNames{
    BitName{kStageDrawIndirect, "draw-indirect"},
    BitName{kStageVertexInput, "vertex-input"},
    BitName{kStageVertexShader, "vertex"},
    BitName{kStageFragmentShader, "fragment"},
    BitName{kStageEarlyFragmentTests, "early-fragment-tests"},
    BitName{kStageLateFragmentTests, "late-fragment-tests"},
    BitName{kStageColorAttachmentOutput, "color-output"},
    BitName{kStageComputeShader, "compute"},
    BitName{kStageTransfer, "transfer"},
    BitName{kStageResolve, "resolve"},
    BitName{kStageHost, "host"},
    BitName{kStageAllCommands, "all-commands"},
};

constexpr std::array kAccessNames{
    BitName{kAccessIndirectCommandRead, "indirect-read"},
    BitName{kAccessIndexRead, "index-read"},
    BitName{kAccessVertexAttributeRead, "vertex-read"},
    BitName{kAccessUniformRead, "uniform-read"},
    BitName{kAccessShaderSampledRead, "sampled-read"},
    BitName{kAccessShaderStorageRead, "storage-read"},
    BitName{kAccessShaderStorageWrite, "storage-write"},
    BitName{kAccessColorAttachmentRead, "color-read"},
    BitName{kAccessColorAttachmentWrite, "color-write"},
    BitName{kAccessDepthStencilRead, "depth-read"},
    BitName{kAccessDepthStencilWrite, "depth-write"},
    BitName{kAccessTransferRead, "transfer-read"},
    BitName{kAccessTransferWrite, "transfer-write"},
    BitName{kAccessHostRead, "host-read"},
    BitName{kAccessHostWrite, "host-write"},
};

// Names of the set bits joined by '+'; bits without a name (none today) are kept as hex, so a new
// bit can never vanish from the dump.
template <std::size_t N>
std::string bitNames(uint32_t mask, const std::array<BitName, N>& names) {
  if (mask == 0) return "none";
  std::string out;
  for (const auto& [bit, name] : names) {
    if ((mask & bit) == 0) continue;
    if (!out.empty()) out += '+';
    out += name;
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
  return bitNames(stages, kStageNames);
}
std::string accessNames(AccessMask access) {
  return bitNames(access, kAccessNames);
}

std::string_view layoutName(Layout layout) {
  switch (layout) {
    case Layout::Undefined:
      return "undefined";
    case Layout::General:
      return "general";
    case Layout::ColorAttachment:
      return "color-attachment";
    case Layout::DepthStencilAttachment:
      return "depth-stencil-attachment";
    case Layout::DepthStencilReadOnly:
      return "depth-stencil-read-only";
    case Layout::ShaderReadOnly:
      return "shader-read-only";
    case Layout::TransferSrc:
      return "transfer-src";
    case Layout::TransferDst:
      return "transfer-dst";
  }
  return "?";
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
