// Queue-family ownership of the scene workload's imported resources on a device where graphics,
// compute and transfer are different families (lavapipe has one family, so the device never
// transfers there: the frame graph is compiled again here with three). Every execution must hand
// ownership over consistently: each acquire of an imported resource pairs with a release of the
// same resource between the same queues in the same compiled graph (a release at the end of one
// execution pairs with the acquire at the start of the next), and vice versa. Otherwise the
// layers report UNASSIGNED-VkBufferMemoryBarrier-buffer-00004 (acquire without release) or -00003
// (a release repeated without an acquire) on every frame.
#include <fgb/graph/compiler.hpp>
#include <fgb/renderer/scene_workload.hpp>

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>

namespace fgb::render {
namespace {

graph::CompiledGraph compileWithThreeFamilies(const graph::FrameGraph& declaration, bool buffersShared) {
  graph::CompileOptions options;
  options.queueCount = 3;
  options.queueOfClass = {0, 1, 2};
  options.familyOfQueue = {0, 2, 1};  // as on the H200: graphics 0, compute 2, transfer 1
  options.buffersShareFamilies = buffersShared;
  return graph::compile(declaration, options);
}

// (resource, src queue, dst queue) -> releases minus acquires, for imported resources.
std::map<std::tuple<uint32_t, uint32_t, uint32_t>, int> unpairedTransfers(const graph::FrameGraph& declaration,
                                                                        const graph::CompiledGraph& compiled) {
  std::map<std::tuple<uint32_t, uint32_t, uint32_t>, int> balance;
  for (const graph::Barrier& b : compiled.barriers) {
    if (b.kind == graph::Barrier::Kind::Transition || !declaration.resources()[b.resource].imported) continue;
    balance[{b.resource, b.srcQueue, b.dstQueue}] += b.kind == graph::Barrier::Kind::Release ? 1 : -1;
  }
  std::erase_if(balance, [](const auto& entry) { return entry.second == 0; });
  return balance;
}

std::unique_ptr<Workload> open(const std::string& scene) {
  WorkloadConfig config;
  config.scenePath = scene;
  config.device = "lavapipe";
  config.width = 160;
  config.height = 90;
  return openSceneWorkload(config);
}

class SceneOwnership : public ::testing::TestWithParam<std::string> {};

void expectPaired(const graph::FrameGraph& declaration, const graph::CompiledGraph& compiled) {
  for (const auto& [key, count] : unpairedTransfers(declaration, compiled)) {
    const auto& [resource, src, dst] = key;
    ADD_FAILURE() << "'" << declaration.resources()[resource].name << "' queue " << src << " -> " << dst << ": "
                  << (count > 0 ? "release(s) without acquire: " : "acquire(s) without release: ") << count;
  }
}

// Exclusive buffers (a backend that does not share them): imported buffers change families on
// every frame, and every transfer must pair up.
TEST_P(SceneOwnership, EveryAcquireOfAnImportPairsWithARelease) {
  const auto workload = open(GetParam());
  const graph::FrameGraph* declaration = frameGraphOf(*workload);
  ASSERT_NE(declaration, nullptr);
  const auto compiled = compileWithThreeFamilies(*declaration, false);
  uint32_t transfers = 0;
  for (const auto& b : compiled.barriers) transfers += b.kind != graph::Barrier::Kind::Transition;
  EXPECT_GT(transfers, 0u) << "three families but no ownership transfer: the check would be vacuous";
  expectPaired(*declaration, compiled);
}

// As the Vulkan backend compiles it (buffers shared by all families): only textures transfer.
TEST_P(SceneOwnership, SharedBuffersNeverTransferAndTexturesPairUp) {
  const auto workload = open(GetParam());
  const graph::FrameGraph* declaration = frameGraphOf(*workload);
  ASSERT_NE(declaration, nullptr);
  const auto compiled = compileWithThreeFamilies(*declaration, true);
  for (const auto& b : compiled.barriers) {
    const bool buffer = declaration->resources()[b.resource].kind == graph::ResourceKind::Buffer;
    EXPECT_FALSE(buffer && b.kind != graph::Barrier::Kind::Transition)
        << "'" << declaration->resources()[b.resource].name << "' is a shared buffer but got an ownership transfer";
  }
  expectPaired(*declaration, compiled);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneOwnership,
                         ::testing::Values(std::string(FGB_RENDERER_TEST_SCENES) + "/atrium-small.json",
                                           std::string(FGB_SCENES_DIR) + "/particles-only.json",
                                           std::string(FGB_SCENES_DIR) + "/lights-only.json"));

}  // namespace
}  // namespace fgb::render
