// Corpus fingerprint: one hash over every field of every CompiledGraph (and every compile error
// and cull diagnostic) of a fixed corpus of random declarations. Refactoring the compiler must not
// change what it produces; a change of behaviour must change kRecordedFingerprint on purpose, in
// the same commit, saying why.
#include <gtest/gtest.h>

#include <cstdint>
#include <fgb/graph/compiler.hpp>
#include <string>

#include "flatten.hpp"
#include "random_graph.hpp"

namespace fgb::graph::test {
namespace {

// Recorded when a transient's first barrier began to make the writes of the earlier occupants of its
// memory available (Placement::aliasedAfterWrites, also flattened now); before, from f6c6001 on:
// 0xe3cb3f83eebd7e97.
constexpr uint64_t kRecordedFingerprint = 0x62f2fe2c0def3882ull;

void addCompile(Fingerprint& f, const FrameGraph& graph, const CompileOptions& options) {
  try {
    f.add(flatten(graph, compile(graph, options)));
  } catch (const GraphError& error) {
    f.add(std::string(error.what()));
  }
}

// Small graphs (5..60 nodes, like property_test's) under every option set, and a few larger ones.
uint64_t corpusFingerprint() {
  Fingerprint f;
  for (uint32_t queues = 1; queues <= 3; ++queues) {
    for (uint32_t seed = 1; seed <= 400; ++seed) {
      const RandomGraph random = makeRandomGraph(seed * 131 + queues, {.nodes = 5 + seed % 56, .queueCount = queues});
      CompileOptions options = randomCompileOptions(queues);
      options.cull = seed % 4 != 1;
      options.alias = seed % 4 != 2;
      options.buffersShareFamilies = seed % 4 == 3;
      addCompile(f, *random.graph, options);
      if (seed % 8 == 0) {  // default options: estimated requirements, families 0/1/2
        CompileOptions defaults;
        defaults.queueCount = queues;
        defaults.queueOfClass = queueOfClassFor(queues);
        addCompile(f, *random.graph, defaults);
      }
    }
    for (uint32_t seed = 1; seed <= 6; ++seed) {
      const double oldReads = seed % 2 == 0 ? 0.0 : 0.002;
      const RandomGraph random = makeRandomGraph(
          seed * 7 + queues, {.nodes = 400 * seed, .queueCount = queues, .oldVersionReadChance = oldReads});
      addCompile(f, *random.graph, randomCompileOptions(queues));
    }
  }
  return f.value();
}

TEST(Fingerprint, CompiledCorpusIsUnchanged) {
  const uint64_t fingerprint = corpusFingerprint();
  EXPECT_EQ(fingerprint, kRecordedFingerprint) << std::hex << "compiled graphs changed: 0x" << fingerprint;
}

}  // namespace
}  // namespace fgb::graph::test
