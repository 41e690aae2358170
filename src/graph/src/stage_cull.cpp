// Stage: culling (Frostbite's flood fill, run as reverse reachability over versions). A node is
// kept when it has a side effect, writes an imported resource, or produces a version that a kept
// node reads. Everything else is culled, with a reason a person can act on.
#include "compile_state.hpp"

#include <algorithm>
#include <string>

namespace fgb::graph::detail {
namespace {

bool writesImported(const FrameGraph& graph, uint32_t node) {
  for (const Use& use : graph.uses(node)) {
    if (use.writeVersion != kInvalidIndex && graph.resources()[use.resource].imported) return true;
  }
  return false;
}

// Appends "'name'" without temporaries: a large graph may cull thousands of nodes.
void appendQuoted(std::string& out, const std::string& name) {
  out += '\'';
  out += name;
  out += '\'';
}

std::string cullDiagnostic(const CompileState& state, uint32_t node, const Adjacency& allReaders) {
  const FrameGraph& graph = state.graph;
  std::string why;
  why.reserve(96);  // one allocation for the usual "writes 'x' vN, none imported; nothing reads them"
  std::string culledReaders;
  std::vector<uint32_t> named;  // readers already listed (a node may read several outputs)
  for (const Use& use : graph.uses(node)) {
    if (use.writeVersion == kInvalidIndex) continue;
    why += why.empty() ? "writes " : ", ";
    appendQuoted(why, graph.resources()[use.resource].name);
    why += " v";
    why += std::to_string(use.writeVersion);
    for (uint32_t i = allReaders.begin(use.writeVersion); i < allReaders.end(use.writeVersion); ++i) {
      const uint32_t reader = allReaders.items[i];
      if (reader == node || std::find(named.begin(), named.end(), reader) != named.end()) continue;
      named.push_back(reader);
      if (!culledReaders.empty()) culledReaders += ", ";
      appendQuoted(culledReaders, graph.nodes()[reader].name);
    }
  }
  if (why.empty()) return "declares no writes and no side effect";
  why += ", none imported; ";
  if (culledReaders.empty()) {
    why += "nothing reads them";
  } else {
    why += "read only by culled nodes ";
    why += culledReaders;
  }
  return why;
}

}  // namespace

void cullNodes(CompileState& state) {
  const FrameGraph& graph = state.graph;
  const uint32_t count = state.nodeCount;
  state.alive.assign(count, state.options.cull ? 0 : 1);
  if (state.options.cull) {
    ScratchVector<uint32_t> stack;
    for (uint32_t n = 0; n < count; ++n) {
      if (graph.nodes()[n].sideEffect || writesImported(graph, n)) {
        state.alive[n] = 1;
        stack.push_back(n);
      }
    }
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      for (const Use& use : graph.uses(n)) {
        if (use.readVersion == kInvalidIndex) continue;
        const uint32_t producer = graph.versions()[use.readVersion].producer;
        if (producer != kInvalidIndex && !state.alive[producer]) {
          state.alive[producer] = 1;
          stack.push_back(producer);
        }
      }
    }
  }

  for (uint32_t n = 0; n < count && !state.anyCulled; ++n) state.anyCulled = !state.alive[n];
  if (!state.anyCulled) return;
  // A version written by a culled node has only culled readers (an alive reader would have kept
  // its producer), so the diagnostics need the readers among culled nodes only.
  ScratchVector<uint8_t> culled(count, 0);
  for (uint32_t n = 0; n < count; ++n) culled[n] = !state.alive[n];
  const Adjacency culledReaders = collectVersionReaders(graph, culled);
  for (uint32_t n = 0; n < count; ++n) {
    if (state.alive[n]) continue;
    NodeInfo& info = state.out.nodes[n];
    info.culled = true;
    bool hasWrites = false;
    for (const Use& use : graph.uses(n)) hasWrites |= use.writeVersion != kInvalidIndex;
    info.reason = hasWrites ? CullReason::OutputsUnread : CullReason::NoOutputs;
    info.why = cullDiagnostic(state, n, culledReaders);
  }
}

}  // namespace fgb::graph::detail
