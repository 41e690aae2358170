// Stage: queue assignment and culling (Frostbite's flood fill, run as reverse reachability over
// versions). A node is kept when it has a side effect, writes an imported resource, or produces a
// version that a kept node reads. Everything else is culled, with a reason; cullDiagnostic() and
// CullDiagnostics put the reason into words a person can act on. Also counts the uses alive nodes
// make of each resource.
#include <string>
#include <unordered_set>
#include <vector>

#include "compile_state.hpp"

namespace fgb::graph {
namespace detail {
namespace {

// Why to cull a node that no kept node reads from; Alive when it is a root of the flood fill after
// all (it has a side effect or writes an imported resource).
CullReason reasonToCull(const CompileState& state, uint32_t node) {
  if (state.graph.nodes()[node].sideEffect) return CullReason::Alive;
  bool writes = false;
  for (const Use& use : state.uses(node)) {
    if (!use.writes()) continue;
    if (state.isImported(use.resource)) return CullReason::Alive;
    writes = true;
  }
  return writes ? CullReason::OutputsUnread : CullReason::NoOutputs;
}

}  // namespace

void cullNodes(CompileState& state) {
  const auto& nodes = state.graph.nodes();
  const auto& versions = state.versions();
  const bool cull = state.options.cull;
  state.queueOf.resize(state.nodeCount);
  state.out.nodes.assign(state.nodeCount, NodeInfo{});
  state.alive.assign(state.nodeCount, cull ? 0 : 1);
  state.aliveUses.assign(state.resourceCount, 0);
  // A version is only ever read by nodes declared after its producer, so one sweep from the last
  // node backwards has settled every reader of a node before it reaches the node itself.
  for (uint32_t n = state.nodeCount; n-- > 0;) {
    NodeInfo& info = state.out.nodes[n];
    info.queue = state.queueOf[n] = state.options.queueOfClass[static_cast<size_t>(nodes[n].queue)];
    if (!state.alive[n]) {
      info.reason = reasonToCull(state, n);
      info.culled = info.reason != CullReason::Alive;
      if (info.culled) continue;
      state.alive[n] = 1;
    }
    // Alive: so is the producer of every version it reads. (The barrier walk counts the alive
    // uses back down to find each resource's last user.)
    for (const Use& use : state.uses(n)) {
      ++state.aliveUses[use.resource];
      if (use.reads() && versions[use.readVersion].producer != kInvalidIndex) {
        state.alive[versions[use.readVersion].producer] = 1;
      }
    }
  }
}

}  // namespace detail

std::string cullDiagnostic(const FrameGraph& graph, const CompiledGraph& compiled, uint32_t node) {
  return CullDiagnostics(graph, compiled).describe(node);
}

CullDiagnostics::CullDiagnostics(const FrameGraph& graph, const CompiledGraph& compiled)
    : graph_(graph), compiled_(compiled) {
  detail::indexVersionReaders(graph, readerStart_, readers_);
}

std::string CullDiagnostics::describe(uint32_t node) const {
  if (!compiled_.nodes[node].culled) return {};
  std::unordered_set<uint32_t> named;  // a reader of several outputs is named once, where first met
  std::string why;
  std::string readerNames;
  for (const detail::Use& use : detail::Declared::uses(graph_, node)) {
    if (!use.writes()) continue;
    why += why.empty() ? "writes " : ", ";
    why.append("'").append(graph_.resources()[use.resource].name).append("'");
    why += " v" + std::to_string(use.writeVersion);
    // Other readers only: a node may read back what it wrote.
    for (uint32_t i = readerStart_[use.writeVersion]; i < readerStart_[use.writeVersion + 1]; ++i) {
      const uint32_t reader = readers_[i];
      if (reader == node || !compiled_.nodes[reader].culled || !named.insert(reader).second) continue;
      if (!readerNames.empty()) readerNames += ", ";
      readerNames.append("'").append(graph_.nodes()[reader].name).append("'");
    }
  }
  if (why.empty()) return "declares no writes and no side effect";
  why += ", none imported; ";
  why += readerNames.empty() ? "nothing reads them" : "read only by culled nodes " + readerNames;
  return why;
}

}  // namespace fgb::graph
