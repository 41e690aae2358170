// Property tests: thousands of random DAGs (fixed seeds, Q = 1..3), each compiled and checked
// against brute-force reference facts (see support/). Declarations that close a cycle through an
// old-version read must be rejected with the cycle's nodes named; all others must compile.
#include "invariants.hpp"
#include "random_graph.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace fgb::graph::test {
namespace {

constexpr uint32_t kGraphsPerQueueCount = 1500;

struct Tally {
  uint32_t compiled = 0;
  uint32_t cyclic = 0;
  uint32_t culledNodes = 0;
  uint32_t syncEdges = 0;
  uint32_t aliasedSavings = 0;  // graphs where aliasing saved memory
};

uint32_t nodesFor(uint32_t seed) { return 5 + seed * 7919u % 56; }  // 5..60, spread over seeds

// Node names quoted in a cycle message, in order ('a' -> 'b' -> 'a').
std::vector<std::string> quotedNames(const std::string& message) {
  std::vector<std::string> names;
  for (size_t open = message.find('\''); open != std::string::npos; open = message.find('\'', open + 1)) {
    const size_t close = message.find('\'', open + 1);
    if (close == std::string::npos) break;
    names.push_back(message.substr(open + 1, close - open - 1));
    open = close;
  }
  return names;
}

// A cycle step is a version edge, or a chain between two readers of one version that differ in
// queue or (textures) layout (the compiler orders those; see the library's version walk).
bool isCycleStep(const GraphModel& model, const Reference& ref, const CompileOptions& options, uint32_t a,
                 uint32_t b) {
  if (std::find(ref.declaredEdges.begin(), ref.declaredEdges.end(), Edge{a, b}) != ref.declaredEdges.end()) {
    return true;
  }
  for (const ModelUse& ua : model.uses) {
    for (const ModelUse& ub : model.uses) {
      if (ua.node != a || ub.node != b || ua.resource != ub.resource || !ua.reads() || ua.readPos != ub.readPos) {
        continue;
      }
      const bool otherQueue = options.queueOfClass[static_cast<size_t>(model.nodeClass[a])] !=
                              options.queueOfClass[static_cast<size_t>(model.nodeClass[b])];
      const bool otherLayout = accessInfo(ua.access, model.nodeType[a]).layout !=
                               accessInfo(ub.access, model.nodeType[b]).layout;
      if (ub.reads() && (otherQueue || (model.kind[ua.resource] == ResourceKind::Texture && otherLayout))) {
        return true;
      }
    }
  }
  return false;
}

void expectNamesARealCycle(const GraphModel& model, const Reference& ref, const CompileOptions& options,
                           const std::string& message, uint32_t seed) {
  EXPECT_FALSE(ref.cycle.empty()) << "seed " << seed << ": false cycle (the declaration is a DAG): " << message;
  const std::vector<std::string> names = quotedNames(message);
  ASSERT_GE(names.size(), 2u) << message;
  EXPECT_EQ(names.front(), names.back()) << message;
  auto indexOf = [&model](const std::string& name) {
    return static_cast<uint32_t>(std::find(model.nodeName.begin(), model.nodeName.end(), name) -
                                 model.nodeName.begin());
  };
  for (size_t i = 0; i + 1 < names.size(); ++i) {
    const uint32_t a = indexOf(names[i]);
    const uint32_t b = indexOf(names[i + 1]);
    ASSERT_LT(std::max(a, b), model.nodeCount()) << message;
    EXPECT_TRUE(isCycleStep(model, ref, options, a, b)) << "seed " << seed << ": " << names[i] << " -> "
                                                        << names[i + 1] << " is no dependency; " << message;
  }
}

// Compiles one random graph and checks everything; returns false after recording a failure.
bool checkOne(uint32_t seed, uint32_t queues, const CompileOptions& options, Tally& tally) {
  const RandomGraph random = makeRandomGraph(seed, {.nodes = nodesFor(seed), .queueCount = queues});
  const Problems declared = checkDeclaration(random.model, *random.graph);
  EXPECT_TRUE(declared.empty()) << "seed " << seed << joinProblems(declared);
  const Reference ref = computeReference(random.model, options.cull);
  CompiledGraph compiled;
  try {
    compiled = compile(*random.graph, options);
  } catch (const GraphError& error) {
    ++tally.cyclic;
    expectNamesARealCycle(random.model, ref, options, error.what(), seed);
    return !ref.cycle.empty();
  }
  if (!ref.cycle.empty()) {
    ADD_FAILURE() << "seed " << seed << ": cyclic declaration compiled";
    return false;
  }
  const Problems problems = checkEverything(random.model, *random.graph, ref, compiled, options);
  EXPECT_TRUE(problems.empty()) << "seed " << seed << ", Q = " << queues << ", " << nodesFor(seed) << " nodes"
                                << joinProblems(problems);
  ++tally.compiled;
  for (const NodeInfo& info : compiled.nodes) tally.culledNodes += info.culled ? 1 : 0;
  tally.syncEdges += static_cast<uint32_t>(compiled.syncEdges.size());
  if (compiled.aliasing.peakBytesAliased < compiled.aliasing.peakBytesUnaliased) ++tally.aliasedSavings;
  return problems.empty();
}

class RandomDags : public ::testing::TestWithParam<uint32_t> {};

TEST_P(RandomDags, EveryInvariantHoldsWithCullingAndAliasing) {
  const uint32_t queues = GetParam();
  const CompileOptions options = randomCompileOptions(queues);
  Tally tally;
  uint32_t failures = 0;
  for (uint32_t seed = 1; seed <= kGraphsPerQueueCount && failures < 5; ++seed) {
    failures += checkOne(seed * 31 + queues, queues, options, tally) ? 0 : 1;
  }
  // The generator must actually exercise what is checked (else the test would pass vacuously).
  EXPECT_GT(tally.compiled, kGraphsPerQueueCount * 8 / 10);
  EXPECT_GT(tally.cyclic, 0u);
  EXPECT_GT(tally.culledNodes, 100u);
  EXPECT_GT(tally.aliasedSavings, tally.compiled / 2);
  if (queues > 1) {
    EXPECT_GT(tally.syncEdges, 1000u);
  }
}

TEST_P(RandomDags, EveryInvariantHoldsWithoutCullingOrAliasing) {
  const uint32_t queues = GetParam();
  CompileOptions options = randomCompileOptions(queues);
  options.cull = false;
  options.alias = false;
  Tally tally;
  uint32_t failures = 0;
  for (uint32_t seed = 1; seed <= kGraphsPerQueueCount / 4 && failures < 5; ++seed) {
    failures += checkOne(seed * 977 + queues, queues, options, tally) ? 0 : 1;
  }
  EXPECT_EQ(tally.culledNodes, 0u);
  EXPECT_GT(tally.compiled, kGraphsPerQueueCount / 8);  // (no overlaps: checked per graph)
}

TEST_P(RandomDags, EveryInvariantHoldsWithBuffersSharedByAllFamilies) {
  const uint32_t queues = GetParam();
  CompileOptions options = randomCompileOptions(queues);
  options.buffersShareFamilies = true;
  Tally tally;
  uint32_t failures = 0;
  for (uint32_t seed = 1; seed <= kGraphsPerQueueCount / 4 && failures < 5; ++seed) {
    failures += checkOne(seed * 613 + queues, queues, options, tally) ? 0 : 1;
  }
  EXPECT_GT(tally.compiled, kGraphsPerQueueCount / 8);
  if (queues > 1) {
    EXPECT_GT(tally.syncEdges, 100u);
  }
}

TEST(RandomDags, DefaultOptionsAndEstimatedRequirementsHold) {
  for (uint32_t queues = 1; queues <= 3; ++queues) {
    CompileOptions options;
    options.queueCount = queues;
    options.queueOfClass = queueOfClassFor(queues);
    Tally tally;
    for (uint32_t seed = 1; seed <= 100; ++seed) checkOne(seed * 7 + 100000, queues, options, tally);
    EXPECT_GT(tally.compiled, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Queues, RandomDags, ::testing::Values(1u, 2u, 3u),
                         [](const ::testing::TestParamInfo<uint32_t>& queues) {
                           return std::string("Q").append(std::to_string(queues.param));
                         });

}  // namespace
}  // namespace fgb::graph::test
