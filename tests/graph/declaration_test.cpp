// The declaration model: nodes and queue classes, imported/transient resources, one version per
// write, the recorded uses, attachments, and the access-kind table.
#include <fgb/graph/barrier_names.hpp>
#include "test_helpers.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

namespace fgb::graph::test {
namespace {

TEST(Declaration, EachWriteCreatesANewVersionOfTheSameResource) {
  FrameGraph graph;
  const TextureHandle v0 = graph.createTexture("hdr", colorDesc());
  NodeBuilder a = graph.addNode("A", NodeType::Compute);
  const TextureHandle v1 = a.write(v0, Access::StorageWrite);
  NodeBuilder b = graph.addNode("B", NodeType::Compute);
  const TextureHandle v2 = b.write(v1, Access::StorageReadWrite);

  EXPECT_NE(v0, v1);
  EXPECT_NE(v1, v2);
  EXPECT_EQ(graph.resourceOf(v0), graph.resourceOf(v2));
  const VersionDecl& second = versionsOf(graph)[v2.version];
  EXPECT_EQ(second.producer, 1u);
  EXPECT_EQ(second.previous, v1.version);
  EXPECT_EQ(versionsOf(graph)[v1.version].previous, v0.version);
  EXPECT_EQ(versionsOf(graph)[v0.version].producer, kInvalidIndex);
  EXPECT_EQ(graph.resources()[0].latestVersion, v2.version);
  EXPECT_EQ(graph.resources()[0].firstVersion, v0.version);
}

TEST(Declaration, ReadReturnsTheSameVersionAndRecordsOnlyAReadVersion) {
  FrameGraph graph;
  const BufferHandle buffer = graph.importBuffer("lights", bufferDesc(), {3}, {}, {});
  NodeBuilder node = graph.addNode("Cull", NodeType::Compute);
  EXPECT_EQ(node.read(buffer, Access::Uniform), buffer);
  const auto uses = usesOf(graph, 0);
  ASSERT_EQ(uses.size(), 1u);
  EXPECT_EQ(uses[0].readVersion, buffer.version);
  EXPECT_EQ(uses[0].writeVersion, kInvalidIndex);
  EXPECT_EQ(uses[0].access, Access::Uniform);
}

TEST(Declaration, ReadWriteRecordsBothVersions) {
  FrameGraph graph;
  const BufferHandle buffer = graph.importBuffer("particles", bufferDesc(), {3}, {}, {});
  NodeBuilder node = graph.addNode("Simulate", NodeType::Compute);
  const BufferHandle next = node.write(buffer, Access::StorageReadWrite);
  const Use& use = usesOf(graph, 0)[0];
  EXPECT_EQ(use.readVersion, buffer.version);
  EXPECT_EQ(use.writeVersion, next.version);
}

// The public view of a node's uses, in declaration order: resource, access and versions.
TEST(Declaration, AccessesListANodesUsesWithTheirVersions) {
  FrameGraph graph;
  const BufferHandle lights = graph.importBuffer("lights", bufferDesc(), {3}, {}, {});
  const TextureHandle hdr = graph.createTexture("hdr", colorDesc());
  NodeBuilder node = graph.addNode("Shade", NodeType::Compute);
  node.read(lights, Access::Uniform);
  const TextureHandle lit = node.write(hdr, Access::StorageWrite);
  const std::vector<ResourceAccess> accesses = graph.accesses(0);
  ASSERT_EQ(accesses.size(), 2u);
  EXPECT_EQ(accesses[0].resource, graph.resourceOf(lights));
  EXPECT_EQ(accesses[0].access, Access::Uniform);
  EXPECT_EQ(accesses[0].readVersion, lights.version);
  EXPECT_EQ(accesses[0].writeVersion, kInvalidIndex);
  EXPECT_EQ(accesses[1].resource, graph.resourceOf(hdr));
  EXPECT_EQ(accesses[1].access, Access::StorageWrite);
  EXPECT_EQ(accesses[1].readVersion, kInvalidIndex);
  EXPECT_EQ(accesses[1].writeVersion, lit.version);
}

TEST(Declaration, QueueClassDefaultsToTheNodeTypeAndCanBeOverridden) {
  FrameGraph graph;
  graph.addNode("g", NodeType::Graphics);
  graph.addNode("c", NodeType::Compute);
  graph.addNode("t", NodeType::Transfer);
  graph.addNode("c-on-graphics", NodeType::Compute, QueueClass::Graphics);
  EXPECT_EQ(graph.nodes()[0].queue, QueueClass::Graphics);
  EXPECT_EQ(graph.nodes()[1].queue, QueueClass::Compute);
  EXPECT_EQ(graph.nodes()[2].queue, QueueClass::Transfer);
  EXPECT_EQ(graph.nodes()[3].queue, QueueClass::Graphics);
  EXPECT_EQ(graph.nodes()[3].type, NodeType::Compute);
}

TEST(Declaration, ImportedAndTransientResourcesKeepTheirDescriptions) {
  FrameGraph graph;
  const ImportState initial{.stages = kStageTransfer, .access = kAccessTransferWrite,
                            .layout = Layout::TransferDst, .queue = QueueClass::Transfer};
  const ImportState final{.layout = Layout::ShaderReadOnly};
  graph.importTexture("out", colorDesc(640, 360), {42}, initial, final);
  graph.createBuffer("scratch", bufferDesc(1024));
  const ResourceDecl& out = graph.resources()[0];
  EXPECT_TRUE(out.imported);
  EXPECT_EQ(out.kind, ResourceKind::Texture);
  EXPECT_EQ(out.external.id, 42u);
  EXPECT_EQ(out.initialState.layout, Layout::TransferDst);
  EXPECT_EQ(out.initialState.queue, QueueClass::Transfer);
  EXPECT_EQ(out.finalState.layout, Layout::ShaderReadOnly);
  EXPECT_EQ(out.texture.extent.width, 640u);
  const ResourceDecl& scratch = graph.resources()[1];
  EXPECT_FALSE(scratch.imported);
  EXPECT_EQ(scratch.kind, ResourceKind::Buffer);
  EXPECT_EQ(scratch.buffer.size, 1024u);
}

TEST(Declaration, AttachmentsRecordUsesAndAttachmentState) {
  FrameGraph graph;
  const TextureHandle color = graph.createTexture("msaa", colorDesc());
  const TextureHandle resolve = graph.createTexture("resolved", colorDesc());
  const TextureHandle depth = graph.createTexture("depth", colorDesc(256, 256, Format::D32Sfloat));
  NodeBuilder pass = graph.addNode("Forward", NodeType::Graphics);
  TextureHandle newColor;
  const TextureHandle newResolve = pass.addColorTargetWithResolve(color, resolve, &newColor);
  const TextureHandle newDepth = pass.setDepthStencil(depth);

  const NodeAttachments& attachments = graph.attachments(0);
  ASSERT_EQ(attachments.color.size(), 1u);
  EXPECT_EQ(attachments.color[0].target, newColor);
  EXPECT_EQ(attachments.color[0].resolveTarget, newResolve);
  EXPECT_EQ(attachments.depth.target, newDepth);
  EXPECT_FALSE(attachments.depth.readOnly);
  const auto uses = usesOf(graph, 0);
  ASSERT_EQ(uses.size(), 3u);
  EXPECT_EQ(uses[0].access, Access::ColorAttachmentWrite);
  EXPECT_EQ(uses[1].access, Access::ResolveDst);
  EXPECT_EQ(uses[2].access, Access::DepthAttachmentWrite);
  EXPECT_EQ(graph.resourceOf(newResolve), graph.resourceOf(resolve));
}

TEST(Declaration, LoadingAttachmentsReadThePreviousContents) {
  FrameGraph graph;
  const TextureHandle color = importOutput(graph, "color");
  const TextureHandle depth = graph.importTexture("depth", colorDesc(256, 256, Format::D32Sfloat), {1}, {}, {});
  NodeBuilder pass = graph.addNode("Overlay", NodeType::Graphics);
  pass.addColorTarget(color, LoadOp::Load);
  pass.setDepthStencil(depth, LoadOp::Load);
  NodeBuilder test = graph.addNode("DepthTest", NodeType::Graphics);
  const TextureHandle latestDepth = graph.attachments(0).depth.target;
  test.setDepthStencilReadOnly(latestDepth);
  EXPECT_EQ(usesOf(graph, 0)[0].access, Access::ColorAttachmentReadWrite);
  EXPECT_EQ(usesOf(graph, 0)[1].access, Access::DepthAttachmentReadWrite);
  EXPECT_EQ(usesOf(graph, 1)[0].access, Access::DepthAttachmentRead);
  EXPECT_EQ(usesOf(graph, 1)[0].writeVersion, kInvalidIndex);
  EXPECT_TRUE(graph.attachments(1).depth.readOnly);
  EXPECT_TRUE(graph.attachments(1).color.empty());
}

TEST(Declaration, SideEffectAndJobAreRecorded) {
  FrameGraph graph;
  int calls = 0;
  graph.addNode("Readback", NodeType::Transfer).sideEffect().setJob([&calls](JobContext&) { ++calls; });
  graph.addNode("Jobless", NodeType::Compute);
  EXPECT_TRUE(graph.nodes()[0].sideEffect);
  const std::vector<Job> jobs = graph.takeJobs();
  ASSERT_EQ(jobs.size(), 2u);  // one per node, empty where none was set
  EXPECT_FALSE(jobs[1]);
  JobContext context;
  jobs[0](context);
  EXPECT_EQ(calls, 1);
}

struct AccessRow {
  Access access;
  bool reads;
  bool writes;
  StageMask stages;  // for a compute node (shader stages derived from the node type)
  AccessMask mask;
  Layout layout;
};

constexpr StageMask kDepthTests = kStageEarlyFragmentTests | kStageLateFragmentTests;

class AccessTable : public ::testing::TestWithParam<AccessRow> {};

TEST_P(AccessTable, MapsToStagesAccessAndLayout) {
  const AccessRow& row = GetParam();
  const AccessInfo info = accessInfo(row.access, NodeType::Compute);
  EXPECT_EQ(info.reads, row.reads) << toString(row.access);
  EXPECT_EQ(info.writes, row.writes) << toString(row.access);
  EXPECT_EQ(info.stages, row.stages) << toString(row.access);
  EXPECT_EQ(info.access, row.mask) << toString(row.access);
  if (row.layout != Layout::Undefined) {
    EXPECT_EQ(info.layout, row.layout) << toString(row.access);
  }
  EXPECT_EQ((info.access & kWriteAccesses) != 0, row.writes) << toString(row.access);
}

INSTANTIATE_TEST_SUITE_P(
    EveryAccessKind, AccessTable,
    ::testing::Values(
        AccessRow{Access::Sampled, true, false, kStageComputeShader, kAccessShaderSampledRead, Layout::ShaderReadOnly},
        AccessRow{Access::StorageRead, true, false, kStageComputeShader, kAccessShaderStorageRead, Layout::General},
        AccessRow{Access::StorageWrite, false, true, kStageComputeShader, kAccessShaderStorageWrite, Layout::General},
        AccessRow{Access::StorageReadWrite, true, true, kStageComputeShader,
                  kAccessShaderStorageRead | kAccessShaderStorageWrite, Layout::General},
        AccessRow{Access::ColorAttachmentWrite, false, true, kStageColorAttachmentOutput,
                  kAccessColorAttachmentWrite, Layout::ColorAttachment},
        AccessRow{Access::ColorAttachmentReadWrite, true, true, kStageColorAttachmentOutput,
                  kAccessColorAttachmentRead | kAccessColorAttachmentWrite, Layout::ColorAttachment},
        AccessRow{Access::DepthAttachmentWrite, false, true, kDepthTests, kAccessDepthStencilWrite,
                  Layout::DepthStencilAttachment},
        AccessRow{Access::DepthAttachmentReadWrite, true, true, kDepthTests,
                  kAccessDepthStencilRead | kAccessDepthStencilWrite, Layout::DepthStencilAttachment},
        AccessRow{Access::DepthAttachmentRead, true, false, kDepthTests, kAccessDepthStencilRead,
                  Layout::DepthStencilReadOnly},
        AccessRow{Access::ResolveDst, false, true, kStageColorAttachmentOutput, kAccessColorAttachmentWrite,
                  Layout::ColorAttachment},
        AccessRow{Access::TransferSrc, true, false, kStageTransfer, kAccessTransferRead, Layout::TransferSrc},
        AccessRow{Access::TransferDst, false, true, kStageTransfer, kAccessTransferWrite, Layout::TransferDst},
        AccessRow{Access::Indirect, true, false, kStageDrawIndirect, kAccessIndirectCommandRead, Layout::Undefined},
        AccessRow{Access::Vertex, true, false, kStageVertexInput, kAccessVertexAttributeRead, Layout::Undefined},
        AccessRow{Access::Index, true, false, kStageVertexInput, kAccessIndexRead, Layout::Undefined},
        AccessRow{Access::Uniform, true, false, kStageComputeShader, kAccessUniformRead, Layout::Undefined},
        AccessRow{Access::HostRead, true, false, kStageHost, kAccessHostRead, Layout::Undefined},
        AccessRow{Access::StorageSampledWrite, false, true, kStageComputeShader,
                  kAccessShaderStorageWrite | kAccessShaderSampledRead, Layout::General}),
    [](const ::testing::TestParamInfo<AccessRow>& row) {
      std::string name(toString(row.param.access));
      std::erase(name, '-');
      return name;
    });

TEST(AccessInfo, ShaderStagesFollowTheNodeTypeUnlessGiven) {
  const AccessInfo graphics = accessInfo(Access::Sampled, NodeType::Graphics);
  EXPECT_NE(graphics.stages & kStageFragmentShader, 0u);
  EXPECT_EQ(graphics.stages & kStageComputeShader, 0u);
  EXPECT_EQ(accessInfo(Access::Sampled, NodeType::Graphics, kStageVertexShader).stages, kStageVertexShader);
  EXPECT_EQ(accessInfo(Access::Uniform, NodeType::Compute).stages, kStageComputeShader);
}

TEST(Declaration, EachUseRecordsWhatAccessInfoSaysForItsAccessNodeTypeAndStages) {
  constexpr NodeType kTypes[] = {NodeType::Graphics, NodeType::Compute, NodeType::Transfer};
  constexpr StageMask kDeclared[] = {kStageNone, kStageVertexShader, kStageComputeShader | kStageFragmentShader};
  for (size_t a = 0; a <= static_cast<size_t>(kLastAccess); ++a) {
    const auto access = static_cast<Access>(a);
    for (const NodeType type : kTypes) {
      for (const StageMask stages : kDeclared) {
        FrameGraph graph;
        const BufferHandle buffer = graph.importBuffer("b", bufferDesc(), {1}, {}, {});
        NodeBuilder node = graph.addNode("N", type);
        if (isWriteAccess(access)) {
          node.write(buffer, access, stages);
        } else {
          node.read(buffer, access, stages);
        }
        const AccessInfo expected = accessInfo(access, type, stages);
        ASSERT_EQ(usesOf(graph, 0).size(), 1u);
        const Use& use = usesOf(graph, 0)[0];
        const std::string what = std::string(toString(access)) + " by a " + std::string(toString(type)) +
                                 " node, stages " + std::to_string(stages);
        EXPECT_EQ(use.stages, expected.stages) << what;
        EXPECT_EQ(use.accessMask, expected.access) << what;
        EXPECT_EQ(use.layout, expected.layout) << what;
        EXPECT_EQ(use.shaderStages, stages) << what;
        EXPECT_EQ(use.readVersion != kInvalidIndex, expected.reads) << what;
        EXPECT_EQ(use.writeVersion != kInvalidIndex, expected.writes) << what;
      }
    }
  }
}

// Names are copied into the graph: they outlive the strings they were declared
// from, survive copies and moves of the graph, and end in a NUL (Vulkan debug labels take them).
TEST(Declaration, NamesAreTheGraphsOwnCopiesAndSurviveCopiesAndMoves) {
  constexpr uint32_t kNodes = 20000;
  auto nameOf = [](uint32_t i) { return "node number " + std::to_string(i); };
  auto expectNames = [&](const FrameGraph& graph, const std::string& longName) {
    ASSERT_EQ(graph.nodes().size(), kNodes + 2);
    for (uint32_t i = 0; i < kNodes; ++i) {
      const std::string_view name = graph.nodes()[i].name;
      ASSERT_EQ(name, nameOf(i));
      ASSERT_EQ(name.data()[name.size()], '\0');
    }
    EXPECT_EQ(graph.nodes()[kNodes].name, longName);
    EXPECT_TRUE(graph.nodes()[kNodes + 1].name.empty());
    EXPECT_EQ(graph.nodes()[kNodes + 1].name.data()[0], '\0');
    EXPECT_EQ(graph.resources()[0].name, "the resource");
  };
  const std::string longName(100000, 'x');  // longer than a block
  FrameGraph copy;
  FrameGraph moved;
  {
    FrameGraph original;
    {
      std::string resourceName = "the resource";
      original.createBuffer(resourceName, bufferDesc());
      resourceName.assign(resourceName.size(), '?');
    }
    for (uint32_t i = 0; i < kNodes; ++i) {
      std::string name = nameOf(i);
      original.addNode(name, NodeType::Compute);
      name.assign(name.size(), '?');  // the graph kept its own copy
    }
    original.addNode(longName, NodeType::Compute);
    original.addNode("", NodeType::Compute);
    expectNames(original, longName);
    copy = original;
    moved = std::move(original);
  }
  expectNames(copy, longName);
  expectNames(moved, longName);
}

// Short names are copied without memcpy, in pieces chosen by length (1-3, 4-7, 8-16 bytes; longer
// ones by memcpy): every length, declared back to back, keeps every byte and its neighbours'.
TEST(Declaration, NamesOfEveryLengthAreCopiedExactly) {
  constexpr size_t kLongest = 40;
  auto nameOf = [](size_t length) {
    std::string name;
    for (size_t i = 0; i < length; ++i) name.push_back(static_cast<char>('a' + (length + i) % 26));
    return name;
  };
  FrameGraph graph;
  for (size_t length = 0; length <= kLongest; ++length) graph.addNode(nameOf(length), NodeType::Compute);
  for (size_t length = 0; length <= kLongest; ++length) {
    const std::string_view name = graph.nodes()[length].name;
    EXPECT_EQ(name, nameOf(length)) << "length " << length;
    EXPECT_EQ(name.data()[name.size()], '\0') << "length " << length;
  }
}

TEST(AccessInfo, QueueClassAndNamesAreStable) {
  EXPECT_EQ(defaultQueue(NodeType::Transfer), QueueClass::Transfer);
  EXPECT_EQ(toString(NodeType::Graphics), "graphics");
  EXPECT_EQ(toString(QueueClass::Compute), "compute");
  EXPECT_FALSE(layoutName(Layout::ShaderReadOnly).empty());
}

}  // namespace
}  // namespace fgb::graph::test
