// Corpus fingerprint: one hash over every field of every CompiledGraph (and every compile error
// and cull diagnostic) of a fixed corpus of random declarations. Refactoring the compiler must not
// change what it produces; a change of behaviour must change kRecordedFingerprint on purpose, in
// the same commit, saying why.
#include "random_graph.hpp"

#include <fgb/graph/compiler.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <string_view>

namespace fgb::graph::test {
namespace {

// Recorded at the commit before the readability rewrite of issue 19 (f6c6001).
constexpr uint64_t kRecordedFingerprint = 0xed10811f76f4f9cbull;

// FNV-1a over values (not raw bytes: padding would make it depend on the compiler).
class Fingerprint {
 public:
  void add(uint64_t value) {
    for (int i = 0; i < 8; ++i) {
      hash_ = (hash_ ^ (value & 0xff)) * 0x100000001b3ull;
      value >>= 8;
    }
  }
  void add(std::string_view text) {
    add(text.size());
    for (char c : text) add(static_cast<uint64_t>(static_cast<unsigned char>(c)));
  }
  template <typename... Values>
  void all(Values... values) {
    (add(static_cast<uint64_t>(values)), ...);
  }
  template <typename T, typename Each>
  void each(const std::vector<T>& items, Each&& each) {
    add(items.size());
    for (const T& item : items) each(item);
  }
  [[nodiscard]] uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

void addCompiled(Fingerprint& f, const FrameGraph& graph, const CompiledGraph& c) {
  f.add(c.queueCount);
  f.each(c.nodes, [&](const NodeInfo& n) { f.all(n.culled, n.reason, n.level, n.queue, n.orderIndex, n.step, n.submit); });
  f.each(c.order, [&](uint32_t n) { f.add(n); });
  f.each(c.edges, [&](const Edge& e) { f.all(e.from, e.to); });
  f.each(c.syncEdges, [&](const Edge& e) { f.all(e.from, e.to); });
  f.each(c.steps, [&](const Step& s) { f.all(s.node, s.before.first, s.before.count, s.after.first, s.after.count); });
  f.each(c.barriers, [&](const Barrier& b) {
    f.all(b.kind, b.resource, b.srcStages, b.srcAccess, b.dstStages, b.dstAccess, b.oldLayout, b.newLayout,
          b.srcQueue, b.dstQueue);
  });
  f.each(c.submits, [&](const Submit& s) {
    f.all(s.queue, s.firstStep, s.stepCount, s.signalValue);
    f.each(s.waits, [&](const SemaphoreWait& w) { f.all(w.queue, w.value, w.stages); });
  });
  f.each(c.submitsPerQueue, [&](uint32_t n) { f.add(n); });
  f.each(c.resources, [&](const ResolvedResource& r) {
    const TextureDesc& t = r.texture;
    f.all(t.format, t.extent.width, t.extent.height, t.extent.depth, t.mipLevels, t.layers, t.samples,
          t.extentFrom.version, t.extentShift);
    f.all(r.buffer.size, r.buffer.sizeFrom.version);
    f.all(r.requirements.size, r.requirements.alignment, r.requirements.memoryTypeBits);
  });
  f.add(c.resourceAlive.size());
  for (const bool alive : c.resourceAlive) f.add(alive);
  f.each(c.lifetimes, [&](const Lifetime& l) { f.all(l.first, l.last); });
  f.each(c.aliasing.placements, [&](const Placement& p) { f.all(p.heap, p.offset, p.size, p.aliasedAfterStages); });
  f.each(c.aliasing.heaps, [&](const Heap& h) { f.all(h.kind, h.memoryTypeBits, h.size, h.alignment); });
  f.all(c.aliasing.peakBytesAliased, c.aliasing.peakBytesUnaliased);
  const CullDiagnostics diagnostics(graph, c);
  for (uint32_t n = 0; n < c.nodes.size(); ++n) f.add(diagnostics.describe(n));
}

void addCompile(Fingerprint& f, const FrameGraph& graph, const CompileOptions& options) {
  try {
    addCompiled(f, graph, compile(graph, options));
  } catch (const GraphError& error) {
    f.add(std::string_view(error.what()));
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
  EXPECT_EQ(corpusFingerprint(), kRecordedFingerprint)
      << std::hex << "compiled graphs changed: 0x" << corpusFingerprint();
}

}  // namespace
}  // namespace fgb::graph::test
