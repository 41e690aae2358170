// Stage: queue assignment and culling (Frostbite's flood fill, run as reverse reachability over
// versions). A node is kept when it has a side effect, writes an imported resource, or produces a
// version that a kept node reads. Everything else is culled, with a reason a person can act on.
#include "compile_state.hpp"

#include <algorithm>
#include <charconv>
#include <string>

namespace fgb::graph::detail {
namespace {

// Appends "'name'" without temporaries: a large graph may cull thousands of nodes.
void appendQuoted(std::string& out, const std::string& name) {
  out += '\'';
  out += name;
  out += '\'';
}

// Culled readers of each version, in declaration order: the diagnostics name them. Built while
// the culling sweep visits nodes backwards (pushing to the front keeps declaration order).
class CulledReaders {
 public:
  void add(const FrameGraph& graph, uint32_t node) {
    if (newest_.empty()) newest_.assign(graph.versions().size(), kInvalidIndex);
    for (const Use& use : graph.uses(node)) {
      if (use.readVersion == kInvalidIndex) continue;
      links_.push_back({node, newest_[use.readVersion]});
      newest_[use.readVersion] = static_cast<uint32_t>(links_.size() - 1);
    }
  }
  template <typename Visit>
  void forEach(uint32_t version, Visit&& visit) const {
    for (uint32_t i = newest_[version]; i != kInvalidIndex; i = links_[i].next) visit(links_[i].node);
  }

 private:
  struct Link {
    uint32_t node;
    uint32_t next;
  };
  ScratchVector<uint32_t> newest_;  // per version: first link, or kInvalidIndex
  ScratchVector<Link> links_;
};

// Writes why `node` was culled into `why` (empty on entry, and usually with capacity left from an
// earlier compile). `readerNames` and `named` are scratch, reused across nodes.
void describeCulled(const FrameGraph& graph, uint32_t node, const CulledReaders& culledReaders, std::string& why,
                    std::string& readerNames, std::vector<uint32_t>& named) {
  readerNames.clear();
  named.clear();  // readers already listed (a node may read several outputs)
  for (const Use& use : graph.uses(node)) {
    if (use.writeVersion == kInvalidIndex) continue;
    why += why.empty() ? "writes " : ", ";
    appendQuoted(why, graph.resources()[use.resource].name);
    char version[16] = {' ', 'v'};  // " v<version>", without a temporary string
    const char* end = std::to_chars(version + 2, version + sizeof version, use.writeVersion).ptr;
    why.append(version, static_cast<size_t>(end - version));
    culledReaders.forEach(use.writeVersion, [&](uint32_t reader) {
      if (reader == node || std::find(named.begin(), named.end(), reader) != named.end()) return;
      named.push_back(reader);
      if (!readerNames.empty()) readerNames += ", ";
      appendQuoted(readerNames, graph.nodes()[reader].name);
    });
  }
  if (why.empty()) {
    why = "declares no writes and no side effect";
    return;
  }
  why += ", none imported; ";
  if (readerNames.empty()) {
    why += "nothing reads them";
  } else {
    why += "read only by culled nodes ";
    why += readerNames;
  }
}

// Overwrites every field (the element may be left over from an earlier compile), keeping the
// diagnostic's capacity.
void resetNodeInfo(NodeInfo& info, uint32_t queue) {
  info.culled = false;
  info.reason = CullReason::Alive;
  info.why.clear();
  info.level = 0;
  info.queue = queue;
  info.orderIndex = kInvalidIndex;
  info.step = kInvalidIndex;
  info.submit = kInvalidIndex;
}

bool isRoot(const CompileState& state, uint32_t node) {
  if (state.graph.nodes()[node].sideEffect) return true;
  for (const Use& use : state.graph.uses(node)) {
    if (use.writeVersion != kInvalidIndex && (state.resourceTraits[use.resource] & kResourceImported) != 0) return true;
  }
  return false;
}

// Starts loading what describing `node` reads and writes: its diagnostic's storage and the
// declarations of what it writes. Culled nodes are scattered, so nothing else would fetch these
// ahead, and the loads would cost more than building the text.
void prefetchDiagnosticOf(const CompileState& state, uint32_t node) {
  __builtin_prefetch(state.out.nodes[node].why.data(), 1);
  for (const Use& use : state.graph.uses(node)) {
    if (use.writeVersion != kInvalidIndex) __builtin_prefetch(&state.graph.resources()[use.resource]);
  }
}

// `culledNodes` in reverse declaration order (as the sweep found them).
void explainCulled(CompileState& state, const CulledReaders& culledReaders,
                   const ScratchVector<uint32_t>& culledNodes) {
  constexpr size_t kLookAhead = 4;
  std::string readerNames;
  ScratchVector<uint32_t> named;
  for (size_t i = culledNodes.size(); i-- > 0;) {
    if (i >= kLookAhead) prefetchDiagnosticOf(state, culledNodes[i - kLookAhead]);
    const uint32_t n = culledNodes[i];
    NodeInfo& info = state.out.nodes[n];
    info.culled = true;
    bool hasWrites = false;
    for (const Use& use : state.graph.uses(n)) hasWrites |= use.writeVersion != kInvalidIndex;
    info.reason = hasWrites ? CullReason::OutputsUnread : CullReason::NoOutputs;
    describeCulled(state.graph, n, culledReaders, info.why, readerNames, named);
  }
}

}  // namespace

void cullNodes(CompileState& state) {
  const FrameGraph& graph = state.graph;
  const auto& versions = graph.versions();
  const uint32_t count = state.nodeCount;
  const bool cull = state.options.cull;
  state.queueOf.resize(count);
  // out.nodes may hold the elements of an earlier compile (see ~CompiledGraph): each is reset below.
  state.out.nodes.resize(count);
  state.alive.assign(count, cull ? 0 : 1);
  // A version is only ever read by nodes declared after its producer, so one sweep from the last
  // node backwards has settled every reader of a node before it reaches the node itself.
  CulledReaders culledReaders;
  ScratchVector<uint32_t> culledNodes;
  for (uint32_t n = count; n-- > 0;) {
    state.queueOf[n] = state.options.queueOfClass[static_cast<size_t>(graph.nodes()[n].queue)];
    resetNodeInfo(state.out.nodes[n], state.queueOf[n]);
    if (!cull) continue;
    if (!state.alive[n] && !isRoot(state, n)) {
      culledNodes.push_back(n);
      culledReaders.add(graph, n);
      continue;
    }
    state.alive[n] = 1;
    for (const Use& use : graph.uses(n)) {
      if (use.readVersion == kInvalidIndex) continue;
      const uint32_t producer = versions[use.readVersion].producer;
      if (producer != kInvalidIndex) state.alive[producer] = 1;
    }
  }
  state.anyCulled = !culledNodes.empty();
  if (state.anyCulled) explainCulled(state, culledReaders, culledNodes);
}

}  // namespace fgb::graph::detail
