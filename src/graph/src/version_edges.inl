// Internal: the version walk that turns declared uses into ordering edges. Shared by cycle
// detection (all nodes) and dependency building (alive nodes), so both see the same rules.
#pragma once

namespace fgb::graph::detail {

// For each resource, versions are visited in creation order (which is the write order). Per version:
//   RAW  producer(v) -> each alive reader of v
//   WAR  each alive reader of the previous alive version -> producer(v)
//   WAW  producer of the previous alive version -> producer(v)
//   and consecutive readers of one version on different queues, or (textures) in different
//   layouts, are chained: an ownership transfer or a layout change is a write in disguise.
// A culled writer is skipped: its version has no alive readers, so the next alive writer is
// ordered directly after the last alive writer and its readers.
template <typename EmitEdge>
void forEachVersionEdge(const FrameGraph& graph, const std::vector<uint8_t>& alive,
                        const std::vector<uint32_t>& queueOf, const Adjacency& readers, EmitEdge&& emit) {
  const auto& versions = graph.versions();
  const auto& resources = graph.resources();
  std::vector<uint32_t> lastAliveVersion(resources.size(), kInvalidIndex);

  auto readerLayout = [&](uint32_t node, uint32_t version) {
    for (const Use& use : graph.uses(node)) {
      if (use.readVersion == version) return use.layout;
    }
    return Layout::Undefined;
  };

  for (uint32_t v = 0; v < versions.size(); ++v) {
    const VersionDecl& version = versions[v];
    const uint32_t producer = version.producer;
    if (producer != kInvalidIndex && !alive[producer]) continue;  // culled writer: skipped
    uint32_t& previous = lastAliveVersion[version.resource];
    if (producer != kInvalidIndex && previous != kInvalidIndex) {
      const uint32_t previousProducer = versions[previous].producer;
      if (previousProducer != kInvalidIndex && previousProducer != producer) emit(previousProducer, producer);
      for (uint32_t i = readers.begin(previous); i < readers.end(previous); ++i) {
        if (readers.items[i] != producer) emit(readers.items[i], producer);
      }
    }
    previous = v;
    const bool texture = resources[version.resource].kind == ResourceKind::Texture;
    uint32_t previousReader = kInvalidIndex;
    Layout previousLayout = Layout::Undefined;
    for (uint32_t i = readers.begin(v); i < readers.end(v); ++i) {
      const uint32_t reader = readers.items[i];
      if (producer != kInvalidIndex && producer != reader) emit(producer, reader);
      const Layout layout = texture ? readerLayout(reader, v) : Layout::General;
      if (previousReader != kInvalidIndex && previousReader != reader &&
          (queueOf[previousReader] != queueOf[reader] || layout != previousLayout)) {
        emit(previousReader, reader);
      }
      previousReader = reader;
      previousLayout = layout;
    }
  }
}

}  // namespace fgb::graph::detail
