// Stage: queue assignment and culling (Frostbite's flood fill, run as reverse reachability over
// versions). A node is kept when it has a side effect, writes an imported resource, or produces a
// version that a kept node reads. Everything else is culled, with a reason; cullDiagnostic() puts
// the reason into words a person can act on. Also counts the uses alive nodes make of each resource.
#include "compile_state.hpp"

#include <algorithm>
#include <string>
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
    if ((state.resourceTraits[use.resource] & kResourceImported) != 0) return CullReason::Alive;
    writes = true;
  }
  return writes ? CullReason::OutputsUnread : CullReason::NoOutputs;
}

}  // namespace

void cullNodes(CompileState& state) {
  const FrameGraph& graph = state.graph;
  const auto& versions = graph.versions();
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
      if (use.readVersion == kInvalidIndex) continue;
      const uint32_t producer = versions[use.readVersion].producer;
      if (producer != kInvalidIndex) state.alive[producer] = 1;
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

}  // namespace

std::string cullDiagnostic(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t node) {
  if (!compiled.nodes[node].culled) return {};
  std::string why;
  std::string readerNames;
  std::vector<uint32_t> named;  // readers already listed (a node may read several outputs)
  for (const Use& use : graph.uses(node)) {
    if (use.writeVersion == kInvalidIndex) continue;
    why += why.empty() ? "writes " : ", ";
    appendQuoted(why, graph.resources()[use.resource].name);
    why += " v" + std::to_string(use.writeVersion);
    forEachCulledReader(graph, compiled, node, use.writeVersion, [&](uint32_t reader) {
      if (std::find(named.begin(), named.end(), reader) != named.end()) return;
      named.push_back(reader);
      if (!readerNames.empty()) readerNames += ", ";
      appendQuoted(readerNames, graph.nodes()[reader].name);
    });
  }
  if (why.empty()) return "declares no writes and no side effect";
  why += ", none imported; ";
  why += readerNames.empty() ? "nothing reads them" : "read only by culled nodes " + readerNames;
  return why;
}

}  // namespace fgb::graph
