// Culling by flood fill from imported resources and side-effect nodes, with a reason per node.
#include "random_graph.hpp"
#include "test_helpers.hpp"

#include <fgb/graph/dot.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace fgb::graph::test {
namespace {

struct Pipeline {
  FrameGraph graph;
  CompiledGraph compiled;
};

// Shadow -> Light -> (out); Debug writes a transient nobody reads; Probe only reads.
Pipeline declareWithDeadBranches(bool cull) {
  Pipeline p;
  FrameGraph& g = p.graph;
  const TextureHandle out = importOutput(g, "out");
  const TextureHandle shadow = g.createTexture("shadow", colorDesc(512, 512, Format::D32Sfloat));
  const TextureHandle debug = g.createTexture("debug-view", colorDesc());
  const TextureHandle shadow1 = g.addNode("Shadow", NodeType::Graphics).setDepthStencil(shadow);
  NodeBuilder light = g.addNode("Light", NodeType::Graphics);
  light.read(shadow1);
  light.addColorTarget(out);
  NodeBuilder dbg = g.addNode("Debug", NodeType::Compute);
  dbg.read(shadow1);
  dbg.write(debug, Access::StorageWrite);
  g.addNode("Probe", NodeType::Compute).read(shadow1);
  CompileOptions options;
  options.cull = cull;
  p.compiled = compile(g, options);
  return p;
}

TEST(Culling, KeepsExactlyTheWorkThatReachesAnImportedResource) {
  const Pipeline p = declareWithDeadBranches(true);
  EXPECT_FALSE(p.compiled.nodes[nodeNamed(p.graph, "Shadow")].culled);
  EXPECT_FALSE(p.compiled.nodes[nodeNamed(p.graph, "Light")].culled);
  EXPECT_TRUE(p.compiled.nodes[nodeNamed(p.graph, "Debug")].culled);
  EXPECT_TRUE(p.compiled.nodes[nodeNamed(p.graph, "Probe")].culled);
  EXPECT_EQ(p.compiled.order.size(), 2u);
  expectAllInvariants(p.graph, p.compiled, {});
}

TEST(Culling, SaysWhyEachNodeWasCulled) {
  const Pipeline p = declareWithDeadBranches(true);
  const NodeInfo& debug = p.compiled.nodes[nodeNamed(p.graph, "Debug")];
  EXPECT_EQ(debug.reason, CullReason::OutputsUnread);
  EXPECT_EQ(cullDiagnostic(p.graph, p.compiled, nodeNamed(p.graph, "Debug")),
            "writes 'debug-view' v5, none imported; nothing reads them");
  const NodeInfo& probe = p.compiled.nodes[nodeNamed(p.graph, "Probe")];
  EXPECT_EQ(probe.reason, CullReason::NoOutputs);
  EXPECT_EQ(cullDiagnostic(p.graph, p.compiled, nodeNamed(p.graph, "Probe")), "declares no writes and no side effect");
  EXPECT_EQ(p.compiled.nodes[nodeNamed(p.graph, "Light")].reason, CullReason::Alive);
  EXPECT_EQ(cullDiagnostic(p.graph, p.compiled, nodeNamed(p.graph, "Light")), "");
}

TEST(Culling, CulledResourcesAreNotAliveAndGetNoMemory) {
  const Pipeline p = declareWithDeadBranches(true);
  const uint32_t debugView = resourceNamed(p.graph, "debug-view");
  EXPECT_FALSE(p.compiled.resourceAlive[debugView]);
  EXPECT_FALSE(p.compiled.lifetimes[debugView].used());
  EXPECT_EQ(p.compiled.aliasing.placements[debugView].heap, kInvalidIndex);
}

TEST(Culling, CanBeTurnedOff) {
  const Pipeline p = declareWithDeadBranches(false);
  for (const NodeInfo& info : p.compiled.nodes) EXPECT_FALSE(info.culled);
  EXPECT_EQ(p.compiled.order.size(), 4u);
  CompileOptions options;
  options.cull = false;
  expectAllInvariants(p.graph, p.compiled, options);
}

// Culled nodes sit between alive ones in declaration order and share their levels (Debug and
// Probe read what Shadow wrote, like Light). Their NodeInfo must say they have no place in the
// schedule.
TEST(Culling, ACulledNodeHasNoPlaceInTheSchedule) {
  const Pipeline p = declareWithDeadBranches(true);
  for (const char* name : {"Debug", "Probe"}) {
    const NodeInfo& info = p.compiled.nodes[nodeNamed(p.graph, name)];
    EXPECT_EQ(info.level, 0u) << name;
    EXPECT_EQ(info.orderIndex, kInvalidIndex) << name;
    EXPECT_EQ(info.step, kInvalidIndex) << name;
    EXPECT_EQ(info.submit, kInvalidIndex) << name;
  }
  EXPECT_EQ(p.compiled.order, (std::vector<uint32_t>{nodeNamed(p.graph, "Shadow"), nodeNamed(p.graph, "Light")}));
  EXPECT_EQ(p.compiled.nodes[nodeNamed(p.graph, "Light")].orderIndex, 1u);
  expectAllInvariants(p.graph, p.compiled, {});
}

TEST(Culling, ACulledConsumerDoesNotKeepItsProducerAlive) {
  FrameGraph g;
  const BufferHandle a = g.createBuffer("a", bufferDesc());
  const BufferHandle b = g.createBuffer("b", bufferDesc());
  const BufferHandle a1 = g.addNode("Producer", NodeType::Compute).write(a, Access::StorageWrite);
  NodeBuilder consumer = g.addNode("Consumer", NodeType::Compute);
  consumer.read(a1, Access::StorageRead);
  consumer.write(b, Access::StorageWrite);
  const CompiledGraph compiled = compile(g);
  EXPECT_TRUE(compiled.nodes[0].culled);
  EXPECT_TRUE(compiled.nodes[1].culled);
  EXPECT_EQ(cullDiagnostic(g, compiled, 0), "writes 'a' v2, none imported; read only by culled nodes 'Consumer'");
  EXPECT_TRUE(compiled.order.empty());
  EXPECT_TRUE(compiled.steps.empty());
}

TEST(Culling, ASideEffectNodeLivesAndKeepsItsInputsProducersAlive) {
  FrameGraph g;
  const BufferHandle stats = g.createBuffer("stats", bufferDesc());
  const BufferHandle unrelated = g.createBuffer("unrelated", bufferDesc());
  const BufferHandle stats1 = g.addNode("Count", NodeType::Compute).write(stats, Access::StorageWrite);
  g.addNode("Other", NodeType::Compute).write(unrelated, Access::StorageWrite);
  g.addNode("Readback", NodeType::Transfer).sideEffect().read(stats1, Access::TransferSrc);
  const CompiledGraph compiled = compile(g);
  EXPECT_FALSE(compiled.nodes[nodeNamed(g, "Count")].culled);
  EXPECT_FALSE(compiled.nodes[nodeNamed(g, "Readback")].culled);
  EXPECT_TRUE(compiled.nodes[nodeNamed(g, "Other")].culled);
  expectAllInvariants(g, compiled, {});
}

TEST(Culling, WritingAnImportedBufferKeepsANodeEvenIfNobodyReadsIt) {
  FrameGraph g;
  const BufferHandle imported = g.importBuffer("history", bufferDesc(), {9}, {}, {});
  g.addNode("Store", NodeType::Compute).write(imported, Access::StorageWrite);
  const CompiledGraph compiled = compile(g);
  EXPECT_FALSE(compiled.nodes[0].culled);
}

// The reference for CullDiagnostics: cullDiagnostic() as it was before the index, scanning the
// uses of every node declared after `node` for each version it writes. Kept here, apart from the
// library, so that the library's text is checked against an independent model.
std::string scannedCullDiagnostic(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t node) {
  if (!compiled.nodes[node].culled) return {};
  auto quoted = [](std::string_view name) {
    std::string text(1, '\'');  // (not "'" + name: GCC 12 then warns -Wrestrict wrongly)
    text += name;
    text += '\'';
    return text;
  };
  std::string why;
  std::string readerNames;
  std::vector<uint32_t> named;  // readers already listed (a node may read several outputs)
  for (const Use& use : usesOf(graph, node)) {
    if (use.writeVersion == kInvalidIndex) continue;
    why += why.empty() ? "writes " : ", ";
    why += quoted(graph.resources()[use.resource].name);
    why += " v" + std::to_string(use.writeVersion);
    for (uint32_t reader = node + 1; reader < compiled.nodes.size(); ++reader) {
      const auto uses = usesOf(graph, reader);
      const bool reads = std::any_of(uses.begin(), uses.end(),
                                     [&](const Use& other) { return other.readVersion == use.writeVersion; });
      if (!compiled.nodes[reader].culled || !reads) continue;
      if (std::find(named.begin(), named.end(), reader) != named.end()) continue;
      named.push_back(reader);
      if (!readerNames.empty()) readerNames += ", ";
      readerNames += quoted(graph.nodes()[reader].name);
    }
  }
  if (why.empty()) return "declares no writes and no side effect";
  why += ", none imported; ";
  why += readerNames.empty() ? "nothing reads them" : "read only by culled nodes " + readerNames;
  return why;
}

size_t occurrences(const std::string& text, const std::string& needle) {
  size_t count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size())) ++count;
  return count;
}

// Producer writes a then b; readers of a are B and C, of b are A and B: B is named once, where
// first met (under a), so the list is B, C, A, not in declaration order. Alive nodes are not named.
TEST(CullDiagnostics, NamesEachCulledReaderOnceInTheOrderOfTheWrites) {
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  const BufferHandle a = g.createBuffer("a", bufferDesc());
  const BufferHandle b = g.createBuffer("b", bufferDesc());
  const BufferHandle c = g.createBuffer("c", bufferDesc());
  NodeBuilder producer = g.addNode("Producer", NodeType::Compute);
  const BufferHandle a1 = producer.write(a, Access::StorageWrite);
  const BufferHandle b1 = producer.write(b, Access::StorageWrite);
  NodeBuilder readerA = g.addNode("A", NodeType::Compute);
  readerA.read(b1, Access::StorageRead);
  readerA.write(c, Access::StorageWrite);
  NodeBuilder readerB = g.addNode("B", NodeType::Compute);
  readerB.read(a1, Access::StorageRead);
  readerB.read(b1, Access::StorageRead);
  g.addNode("C", NodeType::Compute).read(a1, Access::StorageRead);
  g.addNode("Present", NodeType::Graphics).addColorTarget(out);
  const CompiledGraph compiled = compile(g);
  const uint32_t producerNode = nodeNamed(g, "Producer");
  ASSERT_TRUE(compiled.nodes[producerNode].culled);
  const std::string expected = "writes 'a' v" + std::to_string(a1.version) + ", 'b' v" + std::to_string(b1.version) +
                               ", none imported; read only by culled nodes 'B', 'C', 'A'";
  EXPECT_EQ(scannedCullDiagnostic(g, compiled, producerNode), expected);
  EXPECT_EQ(cullDiagnostic(g, compiled, producerNode), expected);
  const CullDiagnostics diagnostics(g, compiled);
  for (uint32_t n = 0; n < g.nodes().size(); ++n) {
    EXPECT_EQ(diagnostics.describe(n), scannedCullDiagnostic(g, compiled, n)) << g.nodes()[n].name;
    EXPECT_EQ(cullDiagnostic(g, compiled, n), scannedCullDiagnostic(g, compiled, n)) << g.nodes()[n].name;
  }
}

TEST(CullDiagnostics, AgreeWithTheScanOnEveryNodeOfRandomGraphs) {
  uint32_t compiledGraphs = 0;
  uint32_t culledNodes = 0;
  uint32_t culledWithCulledReaders = 0;
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    const uint32_t queues = 1 + seed % 3;
    const RandomGraphParams params{.nodes = 10 + seed % 90, .queueCount = queues, .sideEffectChance = 0.02};
    const RandomGraph random = makeRandomGraph(seed * 7 + 11, params);
    CompiledGraph compiled;
    try {
      compiled = compile(*random.graph, randomCompileOptions(queues));
    } catch (const GraphError&) {
      continue;  // a declaration that closes a cycle (the property tests check those)
    }
    ++compiledGraphs;
    const FrameGraph& graph = *random.graph;
    const CullDiagnostics diagnostics(graph, compiled);
    for (uint32_t n = 0; n < graph.nodes().size(); ++n) {
      const std::string expected = scannedCullDiagnostic(graph, compiled, n);
      ASSERT_EQ(diagnostics.describe(n), expected) << "seed " << seed << ", node " << n;
      ASSERT_EQ(cullDiagnostic(graph, compiled, n), expected) << "seed " << seed << ", node " << n;
      culledNodes += compiled.nodes[n].culled ? 1 : 0;
      culledWithCulledReaders += expected.find("read only by culled nodes") != std::string::npos ? 1 : 0;
    }
  }
  // The generator must produce what is compared (else the test would pass vacuously).
  EXPECT_GT(compiledGraphs, 200u);
  EXPECT_GT(culledNodes, 500u);
  EXPECT_GT(culledWithCulledReaders, 100u);
}

// 20,000 nodes, all but two culled: a chain where each link reads the one before, plus one source
// that every link reads. Describing each culled node by a scan of the nodes after it would be
// quadratic; the dump builds one index. No timing is asserted, only that every reason is there.
TEST(CullDiagnostics, AFullDumpOfAGraphOfManyCulledNodesNamesEveryReason) {
  constexpr uint32_t kLinks = 20000;
  FrameGraph g;
  const TextureHandle out = importOutput(g, "out");
  g.addNode("Present", NodeType::Graphics).addColorTarget(out);
  const BufferHandle shared =
      g.addNode("Source", NodeType::Compute).write(g.createBuffer("shared", bufferDesc()), Access::StorageWrite);
  BufferHandle previous{};
  for (uint32_t i = 0; i < kLinks; ++i) {
    const BufferHandle link = g.createBuffer("link " + std::to_string(i), bufferDesc());
    NodeBuilder node = g.addNode("Link " + std::to_string(i), NodeType::Compute);
    node.read(shared, Access::StorageRead);
    if (i > 0) node.read(previous, Access::StorageRead);
    previous = node.write(link, Access::StorageWrite);
  }
  const CompiledGraph compiled = compile(g);
  const auto culled = static_cast<size_t>(
      std::count_if(compiled.nodes.begin(), compiled.nodes.end(), [](const NodeInfo& info) { return info.culled; }));
  ASSERT_EQ(culled, kLinks + 1u);  // all but Present
  const std::string dump = toDot(g, compiled, DotDetail::Full);
  EXPECT_EQ(occurrences(dump, "culled: "), culled);
  EXPECT_EQ(occurrences(dump, "read only by culled nodes "), culled - 1);  // the last link has no reader
  EXPECT_NE(dump.find("culled: writes 'link 41' v"), std::string::npos);
  EXPECT_NE(dump.find(", none imported; read only by culled nodes 'Link 42'\""), std::string::npos);
  EXPECT_NE(dump.find(", none imported; nothing reads them"), std::string::npos);
  EXPECT_NE(dump.find("'Link 0', 'Link 1', 'Link 2'"), std::string::npos);  // Source's readers, in order
  const CullDiagnostics diagnostics(g, compiled);
  for (uint32_t n = 0; n < g.nodes().size(); n += 997) {  // the scan is linear per node: sample it
    EXPECT_EQ(diagnostics.describe(n), scannedCullDiagnostic(g, compiled, n)) << n;
  }
  EXPECT_EQ(diagnostics.describe(nodeNamed(g, "Source")), scannedCullDiagnostic(g, compiled, nodeNamed(g, "Source")));
}

}  // namespace
}  // namespace fgb::graph::test
