#include "flatten.hpp"

#include <initializer_list>

namespace fgb::graph::test {
namespace {

void add(Flattened& f, std::initializer_list<uint64_t> values) {
  f.values.push_back(values.size());  // so that no two different lists flatten alike
  f.values.insert(f.values.end(), values.begin(), values.end());
}

void addResource(Flattened& f, const ResolvedResource& r) {
  const TextureDesc& t = r.texture;
  add(f, {static_cast<uint64_t>(t.format), t.extent.width, t.extent.height, t.extent.depth, t.mipLevels, t.layers,
          t.samples, t.extentFrom.version, t.extentShift, r.buffer.size, r.buffer.sizeFrom.version, r.requirements.size,
          r.requirements.alignment, r.requirements.memoryTypeBits});
}

}  // namespace

Flattened flatten(const FrameGraph& graph, const CompiledGraph& c) {
  Flattened f;
  add(f, {c.queueCount, c.nodes.size(), c.order.size(), c.edges.size(), c.syncEdges.size(), c.steps.size(),
          c.barriers.size(), c.submits.size(), c.submitsPerQueue.size(), c.resources.size(), c.resourceAlive.size(),
          c.lifetimes.size(), c.aliasing.placements.size(), c.aliasing.heaps.size()});
  const CullDiagnostics diagnostics(graph, c);
  for (uint32_t node = 0; node < c.nodes.size(); ++node) {
    const NodeInfo& n = c.nodes[node];
    add(f, {n.culled, static_cast<uint64_t>(n.reason), n.level, n.queue, n.orderIndex, n.step, n.submit});
    f.diagnostics.push_back(diagnostics.describe(node));
  }
  for (const uint32_t node : c.order) add(f, {node});
  for (const Edge& e : c.edges) add(f, {e.from, e.to});
  for (const Edge& e : c.syncEdges) add(f, {e.from, e.to});
  for (const Step& s : c.steps) add(f, {s.node, s.before.first, s.before.count, s.after.first, s.after.count});
  for (const Barrier& b : c.barriers) {
    add(f, {static_cast<uint64_t>(b.kind), b.resource, b.srcStages, b.srcAccess, b.dstStages, b.dstAccess,
            static_cast<uint64_t>(b.oldLayout), static_cast<uint64_t>(b.newLayout), b.srcQueue, b.dstQueue});
  }
  for (const Submit& s : c.submits) {
    add(f, {s.queue, s.firstStep, s.stepCount, s.signalValue, s.waits.size()});
    for (const SemaphoreWait& w : s.waits) add(f, {w.queue, w.value, w.stages});
  }
  for (const uint32_t count : c.submitsPerQueue) add(f, {count});
  for (const ResolvedResource& r : c.resources) addResource(f, r);
  for (const bool alive : c.resourceAlive) add(f, {alive});
  for (const Lifetime& l : c.lifetimes) add(f, {l.first, l.last});
  for (const Placement& p : c.aliasing.placements) add(f, {p.heap, p.offset, p.size, p.aliasedAfterStages, p.aliasedAfterWrites});
  for (const Heap& h : c.aliasing.heaps) add(f, {static_cast<uint64_t>(h.kind), h.memoryTypeBits, h.size, h.alignment});
  add(f, {c.aliasing.peakBytesAliased, c.aliasing.peakBytesUnaliased});
  return f;
}

void Fingerprint::add(uint64_t value) {
  for (int byte = 0; byte < 8; ++byte, value >>= 8) hash_ = (hash_ ^ (value & 0xff)) * 0x100000001b3ull;
}

void Fingerprint::add(const std::string& text) {
  add(text.size());
  for (const char c : text) add(static_cast<uint64_t>(static_cast<unsigned char>(c)));
}

void Fingerprint::add(const Flattened& flat) {
  for (const uint64_t value : flat.values) add(value);
  for (const std::string& text : flat.diagnostics) add(text);
}

}  // namespace fgb::graph::test
