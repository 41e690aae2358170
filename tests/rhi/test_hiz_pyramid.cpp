// "HiZ Build" (hiz_build.comp, render.occlusion=1) against a CPU reference: every texel of every
// level of the pyramid is the smallest depth key of the viewport pixels it covers (the reduction
// hiz_occlusion.glsl documents), at sizes that are odd at several levels and that take one, two
// and three passes of FGB_HIZ_PASS_LEVELS levels.
#include <algorithm>
#include <fgb/rhi/upload.hpp>
#include <random>

#include "features/visbuffer/hiz_pyramid.hpp"
#include "gpu_support.hpp"

namespace fgb::test {
namespace {

// The reference: texel (i, j) of level k is the min of the keys in [i 2^k, (i + 1) 2^k) x
// [j 2^k, (j + 1) 2^k), clamped to the viewport; levels one after another from level 1.
std::vector<uint32_t> referencePyramid(const std::vector<uint32_t>& keys, uint32_t width, uint32_t height) {
  std::vector<uint32_t> pyramid;
  for (uint32_t level = 1; level <= features::hizLevels(width, height); ++level) {
    for (uint32_t j = 0; j < gpu::hizLevelSide(height, level); ++j)
      for (uint32_t i = 0; i < gpu::hizLevelSide(width, level); ++i) {
        uint32_t farthest = UINT32_MAX;
        for (uint32_t y = j << level; y < std::min(height, (j + 1) << level); ++y)
          for (uint32_t x = i << level; x < std::min(width, (i + 1) << level); ++x)
            farthest = std::min(farthest, keys[y * width + x]);
        pyramid.push_back(farthest);
      }
  }
  return pyramid;
}

class HizPyramid : public GpuTest {
 protected:
  // Builds the pyramid of a visibility buffer whose depth keys are `keys` (random triangle ids in
  // the low words, which the build must ignore) and reads it back.
  std::vector<uint32_t> build(const std::vector<uint32_t>& keys, uint32_t width, uint32_t height) {
    std::mt19937 random(7);
    std::vector<uint64_t> visWords(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) visWords[i] = uint64_t{keys[i]} << 32 | random();
    const uint64_t wordBytes = visWords.size() * 8, hizBytes = features::hizKeys(width, height) * 4;
    const auto wordBuffer = device_->createBuffer(
        {"vis words", wordBytes, rhi::kBufferStorage | rhi::kBufferTransferDst, rhi::MemoryUsage::DeviceLocal});
    rhi::uploadBuffer(*device_, wordBuffer, std::as_bytes(std::span(visWords)));
    const auto hizBuffer = device_->createBuffer(
        {"hiz pyramid", hizBytes, rhi::kBufferStorage | rhi::kBufferTransferSrc, rhi::MemoryUsage::DeviceLocal});
    const auto readback = readbackBuffer("hiz readback", hizBytes);
    const auto pipeline = device_->createComputePipeline({"hiz build", "renderer/visbuffer/hiz_build.comp"});

    graph::FrameGraph g;
    const graph::ImportState any{graph::kStageAllCommands,
                                 graph::kAccessShaderStorageRead | graph::kAccessShaderStorageWrite |
                                     graph::kAccessTransferRead | graph::kAccessTransferWrite,
                                 graph::Layout::Undefined};
    const auto source = g.importBuffer("vis words", {wordBytes}, rhi::external(wordBuffer), any, any);
    auto hiz = g.importBuffer("hiz pyramid", {hizBytes}, rhi::external(hizBuffer), any, any);
    auto out = g.importBuffer("hiz readback", {hizBytes}, rhi::external(readback), kHostRead, kHostRead);
    auto node = g.addNode("HiZ Build", graph::NodeType::Compute);
    node.read(source, graph::Access::StorageRead);
    hiz = node.write(hiz, graph::Access::StorageReadWrite);
    node.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      gpu::HizPush push{ctx.storageBufferIndex(source), ctx.storageBufferIndex(hiz), width, height, 0, 0, 0};
      ctx.cmd().bindPipeline(pipeline);
      for (uint32_t pass = 0; pass < features::hizPasses(width, height); ++pass) {  // as the features do
        if (pass > 0) ctx.cmd().computeBarrier();
        push.sourceLevel = pass * FGB_HIZ_PASS_LEVELS;
        ctx.cmd().push(push);
        const auto groups = features::hizPassGroups(width, height, pass);
        ctx.cmd().dispatch(groups.x, groups.y);
      }
    });
    auto copy = g.addNode("Copy back", graph::NodeType::Transfer);
    copy.read(hiz, graph::Access::TransferSrc);
    out = copy.write(out, graph::Access::TransferDst);
    copy.setJob([=](graph::JobContext& c) {
      auto& ctx = rhi::rhiContext(c);
      ctx.cmd().copyBuffer(ctx.buffer(hiz), ctx.buffer(out), hizBytes);
    });
    auto executable = device_->compile(std::move(g), {.name = "hiz build"});
    device_->wait(device_->execute(*executable));
    return words(readback, hizBytes / 4);
  }
};

TEST_F(HizPyramid, EveryLevelIsTheFarthestKeyOfThePixelsItCovers) {
  struct Size {
    uint32_t width, height;
  };
  // 1 x 1: one level; 64 x 64: one full pass; 333 x 97: two passes, odd at most levels;
  // 4100 x 3: three passes, the second and third of one row.
  for (const Size size : {Size{1, 1}, Size{64, 64}, Size{333, 97}, Size{4100, 3}}) {
    SCOPED_TRACE(std::to_string(size.width) + " x " + std::to_string(size.height));
    std::mt19937 random(size.width * 7919u + size.height);
    std::vector<uint32_t> keys(size_t{size.width} * size.height);
    // Mostly large keys, some 0 (no triangle): a min that skipped a pixel would show.
    for (auto& key : keys) key = random() % 8 == 0 ? 0u : 1u + random() % 0x7fffffffu;
    const auto expected = referencePyramid(keys, size.width, size.height);
    const auto built = build(keys, size.width, size.height);
    ASSERT_EQ(built.size(), expected.size());
    const auto differing = std::mismatch(built.begin(), built.end(), expected.begin()).first - built.begin();
    EXPECT_EQ(differing, static_cast<std::ptrdiff_t>(built.size()))
        << "key " << differing << ": " << built[differing] << ", expected " << expected[differing];
  }
}

}  // namespace
}  // namespace fgb::test
