// The barrier plan: stage/access/layout transitions for every hazard (including same-layout RAW
// and WAW), first use from UNDEFINED, imported initial/final states, and queue-family ownership
// release/acquire pairs.
#include "test_helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

namespace fgb::graph::test {
namespace {

bool hasAll(uint32_t mask, uint32_t bits) { return (mask & bits) == bits; }

TEST(Barriers, SameLayoutReadAfterWriteOnAStorageBuffer) {
  FrameGraph g;
  const BufferHandle out = g.importBuffer("out", bufferDesc(), {1}, {}, {});
  const BufferHandle buf = g.createBuffer("counts", bufferDesc());
  const BufferHandle buf1 = g.addNode("Write", NodeType::Compute).write(buf, Access::StorageWrite);
  NodeBuilder reader = g.addNode("Read", NodeType::Compute);
  reader.read(buf1, Access::StorageRead);
  reader.write(out, Access::StorageWrite);
  const CompiledGraph c = compile(g);
  const auto found = barriersAround(c, nodeNamed(g, "Read"), g.resourceOf(buf1), true);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].kind, Barrier::Kind::Transition);
  EXPECT_TRUE(hasAll(found[0].srcStages, kStageComputeShader));
  EXPECT_TRUE(hasAll(found[0].srcAccess, kAccessShaderStorageWrite));
  EXPECT_TRUE(hasAll(found[0].dstStages, kStageComputeShader));
  EXPECT_TRUE(hasAll(found[0].dstAccess, kAccessShaderStorageRead));
  expectAllInvariants(g, c, {});
}

TEST(Barriers, SameLayoutWriteAfterWriteOnAStorageImage) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle out1 = g.addNode("First", NodeType::Compute).write(out, Access::StorageWrite);
  g.addNode("Second", NodeType::Compute).write(out1, Access::StorageWrite);
  const CompiledGraph c = compile(g);
  const auto found = barriersAround(c, nodeNamed(g, "Second"), 0, true);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].oldLayout, Layout::General);
  EXPECT_EQ(found[0].newLayout, Layout::General);
  EXPECT_TRUE(hasAll(found[0].srcAccess, kAccessShaderStorageWrite));
  EXPECT_TRUE(hasAll(found[0].dstAccess, kAccessShaderStorageWrite));
  expectAllInvariants(g, c, {});
}

// A node that samples the image it writes as storage (Access::StorageSampledWrite, e.g. a chain
// of levels): the barrier into it (here the transient's first, from UNDEFINED) is visible to
// sampled reads too, in GENERAL; the one out of it makes only the storage write available.
TEST(Barriers, StorageSampledWriteIsGeneralAndVisibleToSampledReads) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle levels = g.createTexture("levels", colorDesc());
  const TextureHandle levels1 = g.addNode("Chain", NodeType::Compute).write(levels, Access::StorageSampledWrite);
  NodeBuilder tonemap = g.addNode("Tonemap", NodeType::Compute);
  tonemap.read(levels1);
  tonemap.write(out, Access::StorageWrite);
  const CompiledGraph c = compile(g);
  const uint32_t index = g.resourceOf(levels);
  const auto into = barriersAround(c, nodeNamed(g, "Chain"), index, true);
  ASSERT_EQ(into.size(), 1u);
  EXPECT_EQ(into[0].oldLayout, Layout::Undefined);
  EXPECT_EQ(into[0].newLayout, Layout::General);
  EXPECT_TRUE(hasAll(into[0].dstStages, kStageComputeShader));
  EXPECT_TRUE(hasAll(into[0].dstAccess, kAccessShaderStorageWrite | kAccessShaderSampledRead));
  const auto next = barriersAround(c, nodeNamed(g, "Tonemap"), index, true);
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].oldLayout, Layout::General);
  EXPECT_EQ(next[0].newLayout, Layout::ShaderReadOnly);
  EXPECT_EQ(next[0].srcAccess, kAccessShaderStorageWrite);
  expectAllInvariants(g, c, {});
}

TEST(Barriers, ColorTargetThenSampledChangesLayout) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle hdr = g.createTexture("hdr", colorDesc());
  const TextureHandle hdr1 = g.addNode("Forward", NodeType::Graphics).addColorTarget(hdr);
  NodeBuilder tonemap = g.addNode("Tonemap", NodeType::Graphics);
  tonemap.read(hdr1);
  tonemap.addColorTarget(out);
  const CompiledGraph c = compile(g);
  const uint32_t hdrIndex = g.resourceOf(hdr);
  const auto first = barriersAround(c, nodeNamed(g, "Forward"), hdrIndex, true);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].oldLayout, Layout::Undefined);  // first use of a transient
  EXPECT_EQ(first[0].newLayout, Layout::ColorAttachment);
  const auto second = barriersAround(c, nodeNamed(g, "Tonemap"), hdrIndex, true);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0].oldLayout, Layout::ColorAttachment);
  EXPECT_EQ(second[0].newLayout, Layout::ShaderReadOnly);
  EXPECT_TRUE(hasAll(second[0].srcStages, kStageColorAttachmentOutput));
  EXPECT_TRUE(hasAll(second[0].srcAccess, kAccessColorAttachmentWrite));
  EXPECT_TRUE(hasAll(second[0].dstStages, kStageFragmentShader));
  EXPECT_TRUE(hasAll(second[0].dstAccess, kAccessShaderSampledRead));
  expectAllInvariants(g, c, {});
}

TEST(Barriers, ImportedTextureStartsInItsInitialAndEndsInItsFinalLayout) {
  FrameGraph g;
  const TextureHandle image = g.importTexture(
      "image", colorDesc(), {3}, ImportState{.stages = kStageTransfer, .access = kAccessTransferWrite,
                                             .layout = Layout::TransferDst},
      ImportState{.stages = kStageFragmentShader, .access = kAccessShaderSampledRead,
                  .layout = Layout::ShaderReadOnly});
  g.addNode("Paint", NodeType::Compute, QueueClass::Graphics).write(image, Access::StorageReadWrite);
  const CompiledGraph c = compile(g);
  const auto before = barriersAround(c, 0, 0, true);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0].oldLayout, Layout::TransferDst);
  EXPECT_EQ(before[0].newLayout, Layout::General);
  EXPECT_TRUE(hasAll(before[0].srcStages, kStageTransfer));
  EXPECT_TRUE(hasAll(before[0].srcAccess, kAccessTransferWrite));
  const auto after = barriersAround(c, 0, 0, false);
  ASSERT_EQ(after.size(), 1u);
  EXPECT_EQ(after[0].oldLayout, Layout::General);
  EXPECT_EQ(after[0].newLayout, Layout::ShaderReadOnly);
  EXPECT_TRUE(hasAll(after[0].srcAccess, kAccessShaderStorageWrite));
}

// Compute writes a storage image on queue 1; graphics samples it on queue 0 (another family).
TEST(Barriers, CrossFamilyHandOffIsAReleaseAcquirePair) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle ao = g.createTexture("ao", colorDesc());
  const TextureHandle ao1 = g.addNode("AO", NodeType::Compute).write(ao, Access::StorageWrite);
  NodeBuilder light = g.addNode("Light", NodeType::Graphics);
  light.read(ao1);
  light.addColorTarget(out);
  const CompileOptions options = queueOptions(3);
  const CompiledGraph c = compile(g, options);
  const uint32_t aoIndex = g.resourceOf(ao);
  const auto released = barriersAround(c, nodeNamed(g, "AO"), aoIndex, false);
  const auto acquired = barriersAround(c, nodeNamed(g, "Light"), aoIndex, true);
  auto findKind = [](const std::vector<Barrier>& list, Barrier::Kind kind) {
    const auto it = std::find_if(list.begin(), list.end(), [kind](const Barrier& b) { return b.kind == kind; });
    return it == list.end() ? std::optional<Barrier>{} : std::optional<Barrier>{*it};
  };
  const auto release = findKind(released, Barrier::Kind::Release);
  const auto acquire = findKind(acquired, Barrier::Kind::Acquire);
  ASSERT_TRUE(release.has_value());
  ASSERT_TRUE(acquire.has_value());
  for (const Barrier& b : {*release, *acquire}) {
    EXPECT_EQ(b.srcQueue, 1u);
    EXPECT_EQ(b.dstQueue, 0u);
  }
  EXPECT_EQ(release->oldLayout, acquire->oldLayout);
  EXPECT_EQ(release->newLayout, acquire->newLayout);
  EXPECT_TRUE(hasAll(release->srcAccess, kAccessShaderStorageWrite));
  ASSERT_FALSE(acquired.empty());
  EXPECT_EQ(acquired.back().newLayout, Layout::ShaderReadOnly);
  EXPECT_TRUE(hasAll(acquired.back().dstAccess, kAccessShaderSampledRead));
  EXPECT_EQ(edgeNames(g, c.syncEdges), (NamePairs{{"AO", "Light"}}));
  expectAllInvariants(g, c, options);
}

TEST(Barriers, SameFamilyQueuesNeedNoOwnershipTransfer) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle ao = g.createTexture("ao", colorDesc());
  const TextureHandle ao1 = g.addNode("AO", NodeType::Compute).write(ao, Access::StorageWrite);
  NodeBuilder light = g.addNode("Light", NodeType::Graphics);
  light.read(ao1);
  light.addColorTarget(out);
  CompileOptions options = queueOptions(3);
  options.familyOfQueue = {0, 0, 0};
  const CompiledGraph c = compile(g, options);
  for (const Barrier& b : c.barriers) EXPECT_EQ(b.kind, Barrier::Kind::Transition);
  const auto acquired = barriersAround(c, nodeNamed(g, "Light"), g.resourceOf(ao), true);
  ASSERT_EQ(acquired.size(), 1u);
  EXPECT_EQ(acquired[0].newLayout, Layout::ShaderReadOnly);
}

// Buffers created with CONCURRENT sharing change queue family with no release/acquire pair (a
// semaphore still orders them); textures keep their ownership transfers.
TEST(Barriers, SharedBuffersChangeFamilyWithoutOwnershipTransfer) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const BufferHandle counts = g.createBuffer("counts", bufferDesc());
  const TextureHandle ao = g.createTexture("ao", colorDesc());
  NodeBuilder compute = g.addNode("Cull", NodeType::Compute);
  const BufferHandle counts1 = compute.write(counts, Access::StorageWrite);
  const TextureHandle ao1 = compute.write(ao, Access::StorageWrite);
  NodeBuilder light = g.addNode("Light", NodeType::Graphics);
  light.read(counts1, Access::StorageRead);
  light.read(ao1);
  light.addColorTarget(out);
  CompileOptions options = queueOptions(3);
  options.buffersShareFamilies = true;
  const CompiledGraph c = compile(g, options);
  const uint32_t buffer = g.resourceOf(counts);
  const uint32_t texture = g.resourceOf(ao);
  uint32_t textureTransfers = 0;
  for (const Barrier& b : c.barriers) {
    if (b.kind == Barrier::Kind::Transition) continue;
    EXPECT_NE(b.resource, buffer) << "a shared buffer got an ownership transfer";
    textureTransfers += b.resource == texture ? 1 : 0;
  }
  EXPECT_EQ(textureTransfers, 2u);  // release on compute, acquire on graphics
  // Nor any other barrier: the semaphore made the compute write visible on graphics (and a barrier
  // there could not name compute stages on a queue of another family).
  EXPECT_TRUE(barriersAround(c, nodeNamed(g, "Light"), buffer, true).empty());
  EXPECT_EQ(edgeNames(g, c.syncEdges), (NamePairs{{"Cull", "Light"}}));
  expectAllInvariants(g, c, options);
}

// A shared buffer whose final state is on another queue: the barrier after its last use (on a
// transfer queue here) may name only what that queue has: the host part of the final state, none
// of the graphics stages the next user on the final queue will wait with.
TEST(Barriers, SharedBufferEndingOnAnotherQueueKeepsOnlyTheHostPartOfItsFinalState) {
  for (const bool hostReads : {false, true}) {
    FrameGraph g;
    ImportState final{kStageVertexInput, kAccessVertexAttributeRead, Layout::Undefined, QueueClass::Graphics};
    if (hostReads) {
      final.stages |= kStageHost;
      final.access |= kAccessHostRead;
    }
    const BufferHandle vertices = g.importBuffer("vertices", bufferDesc(), {}, {}, final);
    g.addNode("Upload", NodeType::Transfer).write(vertices, Access::TransferDst);
    CompileOptions options = queueOptions(3);
    options.buffersShareFamilies = true;
    const CompiledGraph c = compile(g, options);
    const auto after = barriersAround(c, nodeNamed(g, "Upload"), g.resourceOf(vertices), false);
    if (!hostReads) {
      EXPECT_TRUE(after.empty()) << "the semaphore hands the buffer over; nothing is left for the transfer queue";
    } else {
      ASSERT_EQ(after.size(), 1u);
      EXPECT_EQ(after[0].kind, Barrier::Kind::Transition);
      EXPECT_EQ(after[0].srcStages, kStageTransfer);
      EXPECT_EQ(after[0].dstStages, kStageHost);
      EXPECT_EQ(after[0].dstAccess, kAccessHostRead);
      EXPECT_EQ(after[0].srcQueue, after[0].dstQueue) << "recorded and completed on the transfer queue";
    }
    expectAllInvariants(g, c, options);
  }
}

TEST(Barriers, ReadOnlyDepthAfterDepthWrite) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle depth = g.createTexture("depth", colorDesc(256, 256, Format::D32Sfloat));
  const TextureHandle depth1 = g.addNode("Prepass", NodeType::Graphics).setDepthStencil(depth);
  NodeBuilder forward = g.addNode("Forward", NodeType::Graphics);
  forward.setDepthStencilReadOnly(depth1);
  forward.addColorTarget(out);
  const CompiledGraph c = compile(g);
  const auto found = barriersAround(c, nodeNamed(g, "Forward"), g.resourceOf(depth), true);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].oldLayout, Layout::DepthStencilAttachment);
  EXPECT_EQ(found[0].newLayout, Layout::DepthStencilReadOnly);
  EXPECT_TRUE(hasAll(found[0].srcAccess, kAccessDepthStencilWrite));
  EXPECT_TRUE(hasAll(found[0].dstAccess, kAccessDepthStencilRead));
  expectAllInvariants(g, c, {});
}

TEST(Barriers, StepRangesStayInsideTheBarrierList) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle t = g.createTexture("t", colorDesc());
  const TextureHandle t1 = g.addNode("A", NodeType::Transfer).write(t, Access::TransferDst);
  NodeBuilder b = g.addNode("B", NodeType::Compute);
  b.read(t1, Access::StorageRead);
  b.write(out, Access::StorageWrite);
  for (uint32_t q = 1; q <= 3; ++q) {
    const CompiledGraph c = compile(g, queueOptions(q));
    for (const Step& step : c.steps) {
      EXPECT_LE(step.before.first + step.before.count, c.barriers.size());
      EXPECT_LE(step.after.first + step.after.count, c.barriers.size());
    }
    expectAllInvariants(g, c, queueOptions(q));
  }
}

}  // namespace
}  // namespace fgb::graph::test
