// Stage: queue assignment and culling (Frostbite's flood fill, run as reverse reachability over
// versions). A node is kept when it has a side effect, writes an imported resource, or produces a
// version that a kept node reads. Everything else is culled, with a reason; cullDiagnostic() and
// CullDiagnostics put the reason into words a person can act on. Also counts the uses alive nodes
// make of each resource.
#include "compile_state.hpp"

#include <algorithm>
#include <string>
#include <unordered_set>
#include <vector>

namespace fgb::graph {
namespace detail {
namespace {

// Overwrites every field: the element may be left over from an earlier compile.
void resetNodeInfo(NodeInfo& info, uint32_t queue) {
  info.culled = false;
  info.reason = CullReason::Alive;
  info.level = 0;
  info.queue = queue;
  info.orderIndex = kInvalidIndex;
  info.step = kInvalidIndex;
  info.submit = kInvalidIndex;
}

// Why to cull a node that no kept node reads from; Alive when it is a root of the flood fill after
// all (it has a side effect or writes an imported resource).
CullReason reasonToCull(const CompileState& state, uint32_t node) {
  if (state.graph.nodes()[node].sideEffect) return CullReason::Alive;
  bool writes = false;
  for (const Use& use : state.graph.uses(node)) {
    if (use.writeVersion == kInvalidIndex) continue;
    if (state.isImported(use.resource)) return CullReason::Alive;
    writes = true;
  }
  return writes ? CullReason::OutputsUnread : CullReason::NoOutputs;
}

}  // namespace

void cullNodes(CompileState& state) {
  const FrameGraph& graph = state.graph;
  const auto& nodes = graph.nodes();
  const uint32_t count = state.nodeCount;
  const bool cull = state.options.cull;
  state.queueOf.resize(count);
  // out.nodes may hold the elements of an earlier compile (see ~CompiledGraph): each is reset below.
  state.out.nodes.resize(count);
  state.alive.assign(count, cull ? 0 : 1);
  // Counted here, where each node's uses are walked once it is known to be alive: the barrier walk
  // counts them down to find each resource's last user without a pass of its own.
  state.aliveUses.assign(state.resourceCount, 0);
  uint32_t* const aliveUses = state.aliveUses.data();
  // A version is only ever read by nodes declared after its producer, so one sweep from the last
  // node backwards has settled every reader of a node before it reaches the node itself.
  bool anyCulled = false;
  for (uint32_t n = count; n-- > 0;) {
    const uint32_t queue = state.options.queueOfClass[static_cast<size_t>(nodes[n].queue)];
    state.queueOf[n] = queue;
    NodeInfo& info = state.out.nodes[n];
    resetNodeInfo(info, queue);
    if (cull && !state.alive[n]) {
      const CullReason reason = reasonToCull(state, n);
      if (reason != CullReason::Alive) {
        info.culled = true;
        info.reason = reason;
        anyCulled = true;
        continue;
      }
      state.alive[n] = 1;
    }
    for (const Use& use : graph.uses(n)) {
      ++aliveUses[use.resource];
      if (use.readProducer != kInvalidIndex) state.alive[use.readProducer] = 1;
    }
  }
  state.anyCulled = anyCulled;
}

}  // namespace detail

namespace {

void appendQuoted(std::string& out, std::string_view name) {
  out += '\'';
  out += name;
  out += '\'';
}

bool readsVersion(const FrameGraph& graph, uint32_t node, uint32_t version) {
  const auto uses = graph.uses(node);
  return std::any_of(uses.begin(), uses.end(), [version](const Use& use) { return use.readVersion == version; });
}

// Calls `visit` with every culled node other than `producer` that reads `version`, in declaration
// order. Only nodes declared after its producer can read a version.
template <typename Visit>
void forEachCulledReader(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t producer, uint32_t version,
                         Visit&& visit) {
  for (uint32_t reader = producer + 1; reader < compiled.nodes.size(); ++reader) {
    if (compiled.nodes[reader].culled && readsVersion(graph, reader, version)) visit(reader);
  }
}

// The text of cullDiagnostic(), shared by the scan and the index so the two cannot drift apart.
// `forEachReader(version, visit)` must call `visit` with each culled node declared after `node` that
// reads `version`, once each, in declaration order.
template <typename ForEachReader>
std::string describeCulled(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t node,
                           ForEachReader&& forEachReader) {
  if (!compiled.nodes[node].culled) return {};
  const auto uses = graph.uses(node);
  const auto writes =
      std::count_if(uses.begin(), uses.end(), [](const Use& use) { return use.writeVersion != kInvalidIndex; });
  // A node may read several of the outputs, and is named once, where first met. Readers of one
  // version come once each, so only a node with several writes needs the set (kept off the path
  // of the common single write).
  const bool readersMayRepeat = writes > 1;
  std::unordered_set<uint32_t> named;
  std::string why;
  std::string readerNames;
  for (const Use& use : uses) {
    if (use.writeVersion == kInvalidIndex) continue;
    why += why.empty() ? "writes " : ", ";
    appendQuoted(why, graph.resources()[use.resource].name);
    why += " v" + std::to_string(use.writeVersion);
    forEachReader(use.writeVersion, [&](uint32_t reader) {
      if (readersMayRepeat && !named.insert(reader).second) return;
      if (!readerNames.empty()) readerNames += ", ";
      appendQuoted(readerNames, graph.nodes()[reader].name);
    });
  }
  if (why.empty()) return "declares no writes and no side effect";
  why += ", none imported; ";
  why += readerNames.empty() ? "nothing reads them" : "read only by culled nodes " + readerNames;
  return why;
}

}  // namespace

// One description scans the uses of the nodes declared after `node`: no more than building a
// CullDiagnostics index costs (both O(nodes + uses)), without the index's arrays, so for a single
// call (a test, a log line) the scan is the cheaper one.
std::string cullDiagnostic(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t node) {
  return describeCulled(graph, compiled, node, [&](uint32_t version, auto&& visit) {
    forEachCulledReader(graph, compiled, node, version, visit);
  });
}

CullDiagnostics::CullDiagnostics(const FrameGraph& graph, const CompiledGraph& compiled)
    : graph_(graph), compiled_(compiled) {
  detail::indexVersionReaders(graph, readerStart_, readers_);
}

std::string CullDiagnostics::describe(uint32_t node) const {
  return describeCulled(graph_, compiled_, node, [&](uint32_t version, auto&& visit) {
    const auto first = readers_.begin() + readerStart_[version];
    const auto last = readers_.begin() + readerStart_[version + 1];
    // As in the scan: culled readers declared after `node` (a version's readers always are), each
    // once (a node that reads the version twice is listed twice, next to itself).
    uint32_t previous = kInvalidIndex;
    for (auto reader = std::upper_bound(first, last, node); reader != last; ++reader) {
      if (*reader == previous || !compiled_.nodes[*reader].culled) continue;
      previous = *reader;
      visit(*reader);
    }
  });
}

}  // namespace fgb::graph
